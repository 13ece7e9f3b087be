"""climbsim-ray-sweep REQUEST.json: the Ray driver of `climbsim sweep --ray` (sweep/ray_pool.hpp).

Every variant is one Ray task reserving `cpus_per_variant` CPUs. The task runs the variant's
command on its node (the same checkout and build at the same path as here) into the variant's
run directory, then sends the directory and the command's output back as one tar archive; this
driver writes them into the sweep directory, where a local sweep leaves them. A task whose worker
or node is lost is run again by Ray on another node (max_retries); a variant that ends with an
exit code of its own (completed, fell, failed) is never run again. Events for the sweep go to
stdout as JSON lines (ray_pool.hpp); everything else is said in plain lines.

Exit code: 0 every variant ran, 1 the sweep could not go on ("fatal"), 2 bad request or no
cluster at the address, 4 stopped (SIGINT).
"""

import io
import json
import os
import signal
import socket
import sys
import tarfile
import time

#: Attempts of a variant whose worker or node is lost, beyond the first.
MAX_RETRIES = 3
#: Seconds between two load events.
LOAD_PERIOD_S = 1.0


def emit(event: dict) -> None:
    sys.stdout.write(json.dumps(event) + "\n")
    sys.stdout.flush()


def say(text: str) -> None:
    sys.stdout.write("climbsim-ray-sweep: " + text + "\n")
    sys.stdout.flush()


def run_variant(argv: list, run_dir: str, needs: list) -> dict:
    """The task: runs one variant on this node and returns its run directory as a tar archive.

    A node without the program, the checkout or another file of `needs` at the paths of the
    driver's machine returns {"no_checkout": ...}: the variant cannot run there, which is no
    reason to try again."""
    import ctypes
    import fcntl
    import hashlib
    import shutil
    import subprocess

    node = socket.gethostname()
    try:
        import ray  # on a worker: the node's address as Ray knows it

        node = f"{ray.util.get_node_ip_address()} ({node})"
    except Exception:  # noqa: BLE001 - the host name alone still names the node
        pass
    for path in [argv[0]] + needs:
        if not os.path.exists(path):
            return {"no_checkout": f"node {node} has no {path}: every node needs the checkout and build at the "
                                   f"paths of the machine that starts the sweep (docs/deployment.md#sweeps-on-a-ray-cluster)"}
    # One attempt at a time in a variant's directory on this node: a lost attempt's process
    # dies with its worker (PDEATHSIG), and the lock is free once it has.
    # The lock file goes when its holder is done: a waiter that got the lock of a removed file
    # takes the new one.
    lock_path = "/tmp/climbsim-sweep-" + hashlib.sha1(run_dir.encode()).hexdigest()[:16] + ".lock"
    while True:
        lock = open(lock_path, "a")
        fcntl.flock(lock, fcntl.LOCK_EX)
        if os.path.exists(lock_path) and os.stat(lock_path).st_ino == os.fstat(lock.fileno()).st_ino:
            break
        lock.close()

    def die_with_worker():
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG

    shutil.rmtree(run_dir, ignore_errors=True)
    os.makedirs(os.path.dirname(run_dir), exist_ok=True)
    started = time.monotonic()
    with open(run_dir + ".log", "wb") as log:
        child = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                 preexec_fn=die_with_worker)
        code = child.wait()
    wall_s = time.monotonic() - started
    archive = io.BytesIO()
    with tarfile.open(fileobj=archive, mode="w") as tar:
        if os.path.isdir(run_dir):
            tar.add(run_dir, arcname=os.path.basename(run_dir))
        tar.add(run_dir + ".log", arcname=os.path.basename(run_dir) + ".log")
    os.unlink(lock_path)
    lock.close()
    return {"exit_code": code, "wall_s": wall_s, "node": node, "tar": archive.getvalue()}


def unpack(result: dict, run_dir: str) -> None:
    """The variant's run directory and log from the task's archive, where a local sweep leaves
    them (on a node that shares this file system they are there already, the same bytes)."""
    import shutil

    with tarfile.open(fileobj=io.BytesIO(result["tar"]), mode="r") as tar:
        staging = run_dir + ".unpacking"
        shutil.rmtree(staging, ignore_errors=True)
        os.makedirs(staging)
        if hasattr(tarfile, "tar_filter"):
            tar.extractall(staging, filter="tar")
        else:
            tar.extractall(staging)
    base = os.path.basename(run_dir)
    if os.path.isdir(os.path.join(staging, base)):
        shutil.rmtree(run_dir, ignore_errors=True)
        os.replace(os.path.join(staging, base), run_dir)
    os.replace(os.path.join(staging, base + ".log"), run_dir + ".log")
    shutil.rmtree(staging, ignore_errors=True)


def resolve(address: str, state: str) -> str:
    """`auto`: the cluster `climbsim cluster up` started (its address file `state`), else Ray's own auto."""
    if address != "auto":
        return address
    if state and os.path.exists(state):
        with open(state) as f:
            return f.read().strip()
    return "auto"


def reachable(address: str) -> bool:
    if address == "auto" or ":" not in address:
        return True
    host, port = address.rsplit(":", 1)
    try:
        with socket.create_connection((host, int(port)), timeout=5):
            return True
    except (OSError, ValueError):
        return False


def main() -> int:
    if len(sys.argv) != 2:
        say("usage: climbsim-ray-sweep REQUEST.json")
        return 2
    with open(sys.argv[1]) as f:
        request = json.load(f)
    address = resolve(request["address"], request.get("address_file", ""))
    if not reachable(address):
        emit({"fatal": f"--ray {request['address']}: no Ray cluster answers at {address} "
                       "(`./deploy/climbsim cluster up` starts one here)"})
        return 2
    stop = {"requested": False}
    signal.signal(signal.SIGINT, lambda *_: stop.update(requested=True))
    signal.signal(signal.SIGTERM, lambda *_: stop.update(requested=True))

    import ray  # late: a bad request or address is told without Ray's start-up time

    ray.init(address=address, logging_level="ERROR", log_to_driver=False, configure_logging=True)
    cpus = float(request["cpus_per_variant"])
    largest = max((n["Resources"].get("CPU", 0.0) for n in ray.nodes() if n["Alive"]), default=0.0)
    if largest < cpus:
        emit({"fatal": f"--cpus-per-variant {cpus:g}: no node of the Ray cluster at {address} has that many "
                       f"CPUs (the largest has {largest:g})"})
        return 1
    task = ray.remote(run_variant).options(num_cpus=cpus, max_retries=MAX_RETRIES, retry_exceptions=False)
    pending = {}
    for job in request["jobs"]:
        pending[task.remote(job["argv"], job["dir"], [request["root"]] + request.get("needs", []))] = job
    say(f"{len(pending)} tasks on the Ray cluster at {address} ({len(ray.nodes())} nodes)")
    alive = {n["NodeID"]: n["NodeManagerAddress"] for n in ray.nodes() if n["Alive"]}
    next_load = 0.0
    fatal = None
    by_node = {}
    while pending and not stop["requested"] and fatal is None:
        ready, _ = ray.wait(list(pending), num_returns=1, timeout=0.2)
        for ref in ready:
            job = pending.pop(ref)
            try:
                result = ray.get(ref)
            except ray.exceptions.RayError as e:  # lost beyond its retries, or the cluster failed it
                emit({"lost": job["index"], "reason": str(e).strip().splitlines()[0]})
                continue
            if "no_checkout" in result:
                fatal = result["no_checkout"]
                emit({"fatal": fatal})
                break
            unpack(result, job["dir"])
            by_node[result["node"]] = by_node.get(result["node"], 0) + 1
            emit({"ended": job["index"], "exit_code": result["exit_code"], "wall_s": result["wall_s"],
                  "node": result["node"]})
        now = time.monotonic()
        if now >= next_load:
            next_load = now + LOAD_PERIOD_S
            now_alive = {n["NodeID"]: n["NodeManagerAddress"] for n in ray.nodes() if n["Alive"]}
            for node_id, where in alive.items():
                if node_id not in now_alive:
                    say(f"node {where} left the cluster: its variants run again on the others")
            alive = now_alive
            used = ray.cluster_resources().get("CPU", 0.0) - ray.available_resources().get("CPU", 0.0)
            running = min(len(pending), int(round(max(used, 0.0) / cpus)))
            emit({"load": {"running": running, "queued": len(pending) - running}})
    for ref in pending:
        ray.cancel(ref, force=True)
    if by_node:
        say("variants by node: " + ", ".join(f"{node}: {n}" for node, n in sorted(by_node.items())))
    if fatal is not None:
        return 1
    return 4 if stop["requested"] else 0


if __name__ == "__main__":
    sys.exit(main())
