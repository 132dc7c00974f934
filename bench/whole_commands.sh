#!/usr/bin/env bash
# Issue 34 item 3: W2 at size N as whole commands, the mass and I_xx each one
# `rigor simplify` process (start, parse, integrate, print), RUNS times each. Prints
# the median, min and max of the pair's wall time, each process's CPU time (perf, when
# installed) and peak RSS (GNU time, when installed). Compare with the in-process FLINT figure of
# `bench/compare.py --only W2`.
#
#   bench/whole_commands.sh [RIGOR_BINARY] [N] [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
# The release build: target/<host triple>/release (see .cargo/config.toml).
bin="${1:-${CARGO_TARGET_DIR:-target}/$(rustc -vV | sed -n 's/^host: //p')/release/rigor}"
n="${2:-16}"
runs="${3:-11}"
mass="int(int(int((1+x+y+z)^$n, x, 0, a), y, 0, b), z, 0, c)"
ixx="int(int(int((1+x+y+z)^$n (y^2 + z^2), x, 0, a), y, 0, b), z, 0, c)"
# The clock is bash's own (EPOCHREALTIME, microseconds): a `$(date …)` around the pair
# would put the start-up and exit of two `date` processes inside the window.
times=()
for ((r = 0; r < runs; r++)); do
  start=$EPOCHREALTIME
  "$bin" simplify "$mass" >/dev/null
  "$bin" simplify "$ixx" >/dev/null
  end=$EPOCHREALTIME
  times+=("$((10#${end/./} - 10#${start/./}))")
done
sorted=($(printf '%s\n' "${times[@]}" | sort -n))
median=${sorted[$((runs / 2))]}
printf 'W2 n=%s, two processes, %s runs: median %.2f ms, min %.2f ms, max %.2f ms\n' \
  "$n" "$runs" "$(echo "$median / 1000" | bc -l)" "$(echo "${sorted[0]} / 1000" | bc -l)" \
  "$(echo "${sorted[$((runs - 1))]} / 1000" | bc -l)"
# CPU time of each process (perf's task-clock, mean of RUNS runs): what the pair costs
# without the waits for a core that a loaded machine adds to the wall time.
if command -v perf >/dev/null 2>&1; then
  for e in "$mass" "$ixx"; do
    ms=$(perf stat -x, -e task-clock -r "$runs" "$bin" simplify "$e" 2>&1 >/dev/null |
      awk -F, '/task-clock/ {print $1}')
    echo "  task-clock ${ms} ms: rigor simplify '${e:0:40}…'"
  done
fi
if [ -x /usr/bin/time ]; then
  for e in "$mass" "$ixx"; do
    kb=$( { /usr/bin/time -f '%M' "$bin" simplify "$e" >/dev/null; } 2>&1 | tail -1)
    echo "  peak RSS ${kb} kB: rigor simplify '${e:0:40}…'"
  done
fi
