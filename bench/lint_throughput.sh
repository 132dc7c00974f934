#!/usr/bin/env bash
# Lint throughput on notes without repeats: every lecture-note fixture of the test suite
# (tests/lint and tests/lint/corpus: Markdown, LaTeX, MyST and Obsidian notes, each
# chain written once) linted by one `rigor lint` process, as CI would run it. Prints the
# chains found, the wall time over RUNS runs (median, min, max), the chains per second
# at the median, and the same on one core (taskset) when taskset is installed.
#
#   bench/lint_throughput.sh [RIGOR_BINARY] [RUNS]     (default: the release build, 11)
set -euo pipefail
cd "$(dirname "$0")/.."
# The release build: target/<host triple>/release (see .cargo/config.toml).
bin="${1:-${CARGO_TARGET_DIR:-target}/$(rustc -vV | sed -n 's/^host: //p')/release/rigor}"
runs="${2:-11}"
[ -x "$bin" ] || cargo build --release --quiet
notes=(tests/lint/*.md tests/lint/*.tex tests/lint/corpus/*)
chains=$( ("$bin" lint "${notes[@]}" 2>/dev/null || true) | tail -1 | sed -n 's/^chains: \([0-9]*\),.*/\1/p')
[ -n "$chains" ] || { echo "no summary line from $bin lint" >&2; exit 1; }

measure() {
  local label=$1
  shift
  local times=()
  for ((r = 0; r < runs; r++)); do
    local start end
    # bash's own clock (microseconds): `$(date …)` would put part of a `date` process's
    # life inside the window.
    start=$EPOCHREALTIME
    "$@" lint "${notes[@]}" >/dev/null 2>&1 || true
    end=$EPOCHREALTIME
    times+=("$((10#${end/./} - 10#${start/./}))")
  done
  local sorted
  sorted=($(printf '%s\n' "${times[@]}" | sort -n))
  local median=${sorted[$((runs / 2))]}
  printf '%s: %s notes, %s chains, %s runs: median %.1f ms (min %.1f, max %.1f), %.0f chains/s\n' \
    "$label" "${#notes[@]}" "$chains" "$runs" "$(echo "$median / 1000" | bc -l)" \
    "$(echo "${sorted[0]} / 1000" | bc -l)" "$(echo "${sorted[$((runs - 1))]} / 1000" | bc -l)" \
    "$(echo "$chains * 1000000 / $median" | bc -l)"
}

measure "all cores ($(nproc))" "$bin"
if command -v taskset >/dev/null 2>&1; then
  measure "one core" taskset -c 0 "$bin"
fi
if [ -x /usr/bin/time ]; then
  kb=$( { /usr/bin/time -f '%M' "$bin" lint "${notes[@]}" >/dev/null 2>&1; } 2>&1 | tail -1)
  echo "peak RSS ${kb} kB"
fi
