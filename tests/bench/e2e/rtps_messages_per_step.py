#!/usr/bin/env python3
"""RTPS messages per lockstep step of a run, unsecured or secured (docs/security.md#messages-per-step).

Counts Fast DDS 2.9's sends and receives with uprobes on libfastrtps (perf probe; needs root):
messages sent (RTPSMessageGroup::send) and received (MessageReceiver::processCDRMsg), the
submessages put into them (add_data, add_data_frag, add_heartbeat, add_acknack, add_gap) and
taken out of them (proc_Submsg_*), and the secured messages' protection operations
(AESGCMGMAC_Transform::encode_rtps_message / decode_rtps_message). `perf stat -I 250` counts
them every 250 ms over every process of the run; the stepping phase is the last block of
intervals with more than 100 DATA submessages sent, and the figures per step are that block's
counts minus the idle rate of the 5 s before it (announcements, liveliness), over the steps.

    sudo tests/bench/e2e/rtps_messages_per_step.py --build build [--secure] [--duration 4]

Prints one line per figure: `rtps: per step: sent=.. DATA=.. DATA_FRAG=.. HEARTBEAT=.. ...`.
The QoS file is the run's (CLIMBSIM_QOS_FILE is passed on). The probes it adds are removed when
it ends (an installed uprobe slows every Fast DDS process on the machine); probes that were there
before stay.
"""
import argparse
import collections
import json
import pathlib
import re
import subprocess
import sys
import tempfile

LIB = "/usr/lib/x86_64-linux-gnu/libfastrtps.so.2.9.1"
# probe name -> demangled symbol prefix in LIB (the first match)
PROBES = {
    "send": "eprosima::fastrtps::rtps::RTPSMessageGroup::send()",
    "data": "eprosima::fastrtps::rtps::RTPSMessageGroup::add_data(",
    "frag": "eprosima::fastrtps::rtps::RTPSMessageGroup::add_data_frag(",
    "hb": "eprosima::fastrtps::rtps::RTPSMessageGroup::add_heartbeat(",
    "ack": "eprosima::fastrtps::rtps::RTPSMessageGroup::add_acknack(",
    "gap": "eprosima::fastrtps::rtps::RTPSMessageGroup::add_gap(eprosima::fastrtps::rtps::SequenceNumber_t const&, "
           "eprosima::fastrtps::BitmapRange<eprosima::fastrtps::rtps::SequenceNumber_t, "
           "eprosima::fastrtps::rtps::SequenceNumberDiff, 256u> const&, eprosima::fastrtps::rtps::GUID_t const&)",
    "rmsg": "eprosima::fastrtps::rtps::MessageReceiver::processCDRMsg(",
    "rdata": "eprosima::fastrtps::rtps::MessageReceiver::proc_Submsg_Data(",
    "rfrag": "eprosima::fastrtps::rtps::MessageReceiver::proc_Submsg_DataFrag(",
    "rhb": "eprosima::fastrtps::rtps::MessageReceiver::proc_Submsg_Heartbeat(",
    "rack": "eprosima::fastrtps::rtps::MessageReceiver::proc_Submsg_Acknack(",
    "rgap": "eprosima::fastrtps::rtps::MessageReceiver::proc_Submsg_Gap(",
    "enc": "eprosima::fastrtps::rtps::security::AESGCMGMAC_Transform::encode_rtps_message(",
    "dec": "eprosima::fastrtps::rtps::security::AESGCMGMAC_Transform::decode_rtps_message(",
}
NAMES = {"send": "sent", "data": "DATA", "frag": "DATA_FRAG", "hb": "HEARTBEAT", "ack": "ACKNACK", "gap": "GAP",
         "rmsg": "received", "rdata": "rDATA", "rfrag": "rDATA_FRAG", "rhb": "rHEARTBEAT", "rack": "rACKNACK",
         "rgap": "rGAP", "enc": "encoded", "dec": "decoded"}
INTERVAL_S = 0.25


def install_probes():
    """Adds the uprobes that are missing, by the symbols' addresses in LIB; returns their names."""
    added = []
    have = subprocess.run(["perf", "probe", "-l"], capture_output=True, text=True).stdout
    symbols = subprocess.run(["nm", "-DC", LIB], capture_output=True, text=True, check=True).stdout.splitlines()
    for name, prefix in PROBES.items():
        if f"probe_libfastrtps:{name} " in have:
            continue
        line = next((s for s in symbols if s.split(" ", 2)[-1].startswith(prefix)), None)
        if line is None:
            sys.exit(f"{LIB}: no symbol {prefix}")
        subprocess.run(["perf", "probe", "-q", "-x", LIB, "-a", f"{name}=0x{line.split()[0]}"], check=True)
        added.append(name)
    return added


def remove_probes(names):
    """Deletes the uprobes install_probes added."""
    for name in names:
        subprocess.run(["perf", "probe", "-q", "-d", f"probe_libfastrtps:{name}"], check=False)


def intervals(perf_csv):
    """{interval end time [s]: {probe: count}} from `perf stat -I -x,` output."""
    rows = collections.defaultdict(dict)
    for line in pathlib.Path(perf_csv).read_text().splitlines():
        fields = line.strip().split(",")
        if len(fields) < 4 or not fields[1].isdigit():
            continue
        rows[float(fields[0])][fields[3].split(":")[-1]] = int(fields[1])
    return rows


def per_step(rows, steps):
    """Counts per step in the stepping block, net of the idle rate before it."""
    times = sorted(rows)
    busy = [i for i, t in enumerate(times) if rows[t].get("data", 0) > 100]
    if not busy:
        sys.exit("no stepping phase in the counts (no interval with more than 100 DATA sent)")
    last = busy[-1]
    first = last
    while first > 0 and rows[times[first - 1]].get("data", 0) > 100:
        first -= 1
    block = times[first:last + 1]
    idle = times[max(0, first - int(5 / INTERVAL_S)):first]
    out = {}
    for name in PROBES:
        total = sum(rows[t].get(name, 0) for t in block)
        idle_rate = sum(rows[t].get(name, 0) for t in idle) / max(1, len(idle))
        out[name] = (total - idle_rate * len(block)) / steps
    return out, len(block) * INTERVAL_S, (sum(rows[t].get("send", 0) for t in idle) / max(1, len(idle))) / INTERVAL_S


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--root", default=".")
    parser.add_argument("--scenario", default="crack-descent")
    parser.add_argument("--duration", default="4", help="simulated seconds (--set duration_s=)")
    parser.add_argument("--secure", action="store_true", help="run --secure")
    args = parser.parse_args()
    added = install_probes()
    try:
        with tempfile.TemporaryDirectory() as tmp:
            run = [f"{args.build}/bin/climbsim-compose", "--root", args.root, "--build", args.build, "run", args.scenario,
                   "--set", f"duration_s={args.duration}", "--out", f"{tmp}/run"] + (["--secure"] if args.secure else [])
            perf = ["perf", "stat", "-I", str(int(INTERVAL_S * 1000)), "-x,", "-o", f"{tmp}/perf.csv", "-e",
                    "probe_libfastrtps:*", "--"]
            log = subprocess.run(perf + run, capture_output=True, text=True)
            if log.returncode != 0:
                sys.exit(f"the run failed (exit code {log.returncode}): {log.stderr.strip().splitlines()[-1:]}")
            summary = json.loads(pathlib.Path(f"{tmp}/run/summary.json").read_text())
            steps = int(re.search(r"end of run after (\d+) steps", log.stdout + log.stderr).group(1))
            counts, block_s, idle_sent = per_step(intervals(f"{tmp}/perf.csv"), steps)
    finally:
        remove_probes(added)
    load = pathlib.Path("/proc/loadavg").read_text().split()[:3]
    print(f"rtps: {args.scenario} {'secured' if args.secure else 'unsecured'}: {steps} steps in a stepping block of "
          f"{block_s:.2f} s, realtime_factor {summary['realtime_factor']:.2f}, load {' '.join(load)}; idle "
          f"{idle_sent:.0f} messages sent per s")
    print("rtps: per step: " + " ".join(f"{NAMES[k]}={v:.2f}" for k, v in counts.items()))


if __name__ == "__main__":
    main()
