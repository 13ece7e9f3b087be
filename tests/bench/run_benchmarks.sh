#!/usr/bin/env bash
# Runs the climbsim benchmarks (docs/benchmarks.md): each prints lines `bench: NAME:
# metric=value ...` and writes BUILDDIR/bench/NAME.json. Called by `./deploy/climbsim bench [NAME
# [ARGS...]]`.
#
# usage: run_benchmarks.sh BUILDDIR [NAME [ARGS...]]
#   NAME   run only this benchmark; ARGS go to it (e.g. `clock --repeat 1 --reads ring`)
# Exit status: non-zero if a benchmark failed to run (a missed target is reported, not failed).
set -euo pipefail

usage() { echo "usage: $0 BUILDDIR [NAME [ARGS...]]  (benchmarks: ${BENCHMARKS[*]})" >&2; }

BENCHMARKS=(clock thermo scene scene-crack-descent sealing drive solo start fidelity sweep e2e e2e-hires)

[[ $# -ge 1 ]] || { usage; exit 2; }
BUILD="$(cd "$1" && pwd)"
shift
OUT="$BUILD/bench"
mkdir -p "$OUT"

# clock: lockstep steps/s with 1, 3, 5 idle participants vs. the raw DDS ping-pong round trip.
bench_clock() {
  "$BUILD/bin/climbsim-bench-clock" --bin-dir "$BUILD/bin" --out "$OUT/clock.json" \
    --log-dir "$OUT/clock-logs" "$@"
}

# thermo: the airflow model alone, real-time factor and implicit vs explicit integrator work.
bench_thermo() {
  "$BUILD/bin/climbsim-bench-thermo" --out "$OUT/thermo.json" "$@"
}

# scene-crack-descent: the default run's depth frames on crack-descent's poses (what the scene
# renders per frame, the whole image, the renderer against its reference path).
bench_scene-crack-descent() {
  "$BUILD/bin/climbsim-bench-scene" --crack-descent --out "$OUT/scene-crack-descent.json" "$@"
}

# e2e-hires: crack-descent-hires (leakage-bound) with 1 renderer of the whole image + 1 sealing
# shard, 1 renderer of the sealing's pixels + 1 shard, and 2 + 2, in rounds (median ratios), and
# with the test hosts up the bytes per step between hosts.
bench_e2e-hires() {
  "$BUILD/bin/climbsim-bench-e2e" --hires --out "$OUT/e2e-hires.json" "$@"
}

# e2e: the whole closed loop (deploy/compose.yaml, crack-descent), real-time factor and CPU shares.
# Any other benchmark NAME is the program climbsim-bench-NAME, told where to write its JSON.
bench_generic() {
  local name="$1"
  shift
  local exe="$BUILD/bin/climbsim-bench-$name"
  [[ -x "$exe" ]] || { echo "run_benchmarks: $exe is not built" >&2; return 1; }
  "$exe" --out "$OUT/$name.json" "$@"
}

selected=("${BENCHMARKS[@]}")
args=()
if [[ $# -ge 1 ]]; then
  name="$1"
  shift
  if [[ " ${BENCHMARKS[*]} " != *" $name "* ]]; then
    echo "run_benchmarks: unknown benchmark '$name'" >&2
    usage
    exit 2
  fi
  selected=("$name")
  args=("$@")
fi

failed=()
for name in "${selected[@]}"; do
  echo "run_benchmarks: $name" >&2
  runner=(bench_generic "$name")
  declare -F "bench_$name" >/dev/null && runner=("bench_$name")
  if ! "${runner[@]}" "${args[@]+"${args[@]}"}"; then
    failed+=("$name")
  fi
done

# The table of docs/benchmarks.md, from every build/bench/*.json there is; after one benchmark
# (NAME given), only its rows: the others keep what the document has.
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
only=()
[[ ${#selected[@]} -eq 1 ]] && only=(--only "${selected[0]}")
if ! python3 "$ROOT/docs/tools/bench_table.py" --bench-dir "$OUT" --doc "$ROOT/docs/benchmarks.md" "${only[@]+"${only[@]}"}"; then
  failed+=("docs/benchmarks.md's table")
fi

if [[ ${#failed[@]} -gt 0 ]]; then
  echo "run_benchmarks: failed: ${failed[*]}" >&2
  exit 1
fi
