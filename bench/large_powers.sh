#!/usr/bin/env bash
# Large powers of sums (#14 item 5): `rigor check` on each claim below, one file per
# claim, timed as a whole process. Each ran out its 10 s budget when powers were
# written out in full; kept factored they take milliseconds. Prints each claim's
# median wall time over RUNS runs and its verdict line.
#
#   bench/large_powers.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-5}"
cargo build --release --quiet
# The release build: target/<host triple>/release (see .cargo/config.toml).
bin="${CARGO_TARGET_DIR:-target}/$(rustc -vV | sed -n 's/^host: //p')/release/rigor"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
claims=(
  "(x - a)^6000 = (x - a)^6000"
  "(x - 1)^6000 = (1 - x)^6000"
  "diff((x - a)^6000, x) = 6000 (x - a)^5999"
  "(x^2 - a^2)^6000 = (x - a)^6000 (x + a)^6000"
  "(x - a)^6000 = (x - a)^5999"
  "abs(x^2 - 4) = abs(x - 2) abs(x + 2)"
)
for c in "${claims[@]}"; do
  printf 'symbols x a\nclaim %s\n' "$c" > "$dir/c.deriv"
  times=()
  for ((r = 0; r < runs; r++)); do
    start=$(date +%s%N)
    line=$("$bin" check "$dir/c.deriv" 2>/dev/null | tail -1 || true)
    end=$(date +%s%N)
    times+=("$(((end - start) / 1000000))")
  done
  median=$(printf '%s\n' "${times[@]}" | sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  printf '%6s ms  %-48s %s\n' "$median" "$c" "$(echo "$line" | sed 's/files: 1, claims: 1, links: 1, //')"
done
