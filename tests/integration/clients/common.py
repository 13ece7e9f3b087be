"""Shared helpers of the client integration tests: build paths, a DDS domain lease as the C++
tests take it (climbsim::DomainLease, flock on /tmp/climbsim-domains/<id>.lock), processes
with logs, launcher runs and trace columns."""

from __future__ import annotations

import csv
import fcntl
import math
import os
import subprocess
from pathlib import Path

ROOT = Path(os.environ["CLIMBSIM_ROOT"])
BUILD = Path(os.environ["CLIMBSIM_BUILD_DIR"])
BIN = BUILD / "bin"
RUNS = BUILD / "test-runs"


class DomainLease:
    """Holds the first free domain id of [first, last] while it lives."""

    def __init__(self, first: int = 100, last: int = 199, lock_dir: str = "/tmp/climbsim-domains") -> None:
        os.makedirs(lock_dir, exist_ok=True)
        for domain in range(first, last + 1):
            fd = os.open(f"{lock_dir}/{domain}.lock", os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o666)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                os.close(fd)
                continue
            self.id, self._fd = domain, fd
            return
        raise RuntimeError(f"no free DDS domain id in {first}..{last} (locks in {lock_dir})")

    def release(self) -> None:
        os.close(self._fd)


def start(args: list, log: Path, env: dict | None = None) -> subprocess.Popen:
    log.parent.mkdir(parents=True, exist_ok=True)
    with open(log, "w") as out:
        return subprocess.Popen([str(a) for a in args], stdout=out, stderr=subprocess.STDOUT,
                                env={**os.environ, **(env or {})})


def compose_run(tag: str, args: list[str], timeout_s: float = 600) -> tuple[int, Path, str]:
    """`climbsim-compose run ARGS --out <runs>/<tag>`: (exit code, run dir, launcher output)."""
    out_dir = RUNS / tag
    log = RUNS / f"{tag}.log"
    proc = start([BIN / "climbsim-compose", "--root", ROOT, "--build", BUILD, "run", *args, "--name", tag,
                  "--out", out_dir], log)
    try:
        code = proc.wait(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        proc.terminate()
        proc.wait(timeout=30)
        code = -1
    return code, out_dir, log.read_text()


def compose_copy(source: str, tag: str, replace: dict[str, str] | None = None) -> Path:
    """A copy of deploy/<source> under its own composition name, its scenario path absolute
    (`ps` and state.json then tell the tests' compositions apart), each key of `replace` in its
    text replaced by its value."""
    text = (ROOT / "deploy" / source).read_text()
    for old, new in (replace or {}).items():
        if old not in text:
            raise AssertionError(f"deploy/{source} has no '{old}'")
        text = text.replace(old, new)
    lines = []
    for line in text.splitlines():
        if line.startswith("name:"):
            line = f"name: test-{tag}"
        elif line.startswith("scenario:"):
            line = f"scenario: {ROOT / 'deploy' / line.split(':', 1)[1].split('#')[0].strip()}"
        lines.append(line)
    path = RUNS / f"{tag}.compose.yaml"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")
    return path


def trace_column(trace: Path, name: str) -> list[float]:
    with open(trace) as f:
        return [float(row[name]) for row in csv.DictReader(f)]


def finite(values: list[float]) -> list[float]:
    return [v for v in values if math.isfinite(v)]


def mean_after(values: list[float], first: int) -> float:
    """Mean of the finite values from row `first` on."""
    held = finite(values[first:])
    return sum(held) / len(held)
