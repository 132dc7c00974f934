#!/usr/bin/env bash
# `rigor mark` on a class of 1,000 submissions (the 8 of tests/mark/class — correct
# ones, each common mistake, a syntax error, a binary file — repeated), against
# tests/mark/reference.deriv. Prints each run's wall time and the median; the target
# (#17) is under 2 s on 2 cores.
#
#   bench/mark_class.sh [N_SUBMISSIONS] [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
n="${1:-1000}"
runs="${2:-5}"
cargo build --release --quiet
# The release build: target/<host triple>/release (see .cargo/config.toml).
bin="${CARGO_TARGET_DIR:-target}/$(rustc -vV | sed -n 's/^host: //p')/release/rigor"
class="$(mktemp -d)"
trap 'rm -rf "$class"' EXIT
mapfile -t subs < <(ls tests/mark/class)
for ((i = 0; i < n; i++)); do
  f="${subs[$((i % ${#subs[@]}))]}"
  cp "tests/mark/class/$f" "$class/$(printf %05d "$i")_$f"
done
times=()
for ((r = 0; r < runs; r++)); do
  start=$(date +%s%N)
  "$bin" mark --reference tests/mark/reference.deriv "$class" --format csv >/dev/null
  end=$(date +%s%N)
  ms=$(((end - start) / 1000000))
  times+=("$ms")
  echo "run $((r + 1)): $ms ms"
done
median=$(printf '%s\n' "${times[@]}" | sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
echo "$n submissions, $(nproc) cores: median $median ms"
