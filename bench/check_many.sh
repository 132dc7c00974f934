#!/usr/bin/env bash
# Issue 34 item 4: `rigor check` of a folder of many handout files, on one core and on
# two (cores 0 and 1). The files are made from derivations/: copies of each handout,
# every copy with a comment line of its own (so no two files are the same text) and every
# other copy, where that leaves the verdicts unchanged (checked once per handout and
# symbol), with one declared symbol renamed (`omega` → `omega_17`). Each configuration
# runs RUNS times, the two interleaved; the script prints the median, min and max wall
# time, the CPU time (user + sys) of every run, and the largest peak RSS (GNU time).
# `taskset -c 0` pins the process to one core, and rigor then starts one worker (one per
# core it may use, `std::thread::available_parallelism`).
#
#   bench/check_many.sh [RIGOR_BINARY] [FILES] [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
# The release build: target/<host triple>/release (see .cargo/config.toml).
bin="${1:-${CARGO_TARGET_DIR:-target}/$(rustc -vV | sed -n 's/^host: //p')/release/rigor}"
files="${2:-1000}"
runs="${3:-5}"
if [ ! -x /usr/bin/time ] || ! command -v taskset >/dev/null; then
  echo "check_many.sh needs GNU time (/usr/bin/time) and taskset" >&2
  exit 1
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

python3 - "$bin" "$files" "$dir" <<'EOF'
import os, re, subprocess, sys

rigor, count, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
src = sorted(f for f in os.listdir("derivations") if f.endswith(".deriv"))
texts = {f: open(os.path.join("derivations", f), encoding="utf-8").read() for f in src}

def summary(text, scratch):
    """rigor's exit code and summary line for `text`."""
    path = os.path.join(scratch, "probe.deriv")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text)
    r = subprocess.run([rigor, "check", path], capture_output=True, text=True)
    return r.returncode, r.stdout.strip().splitlines()[-1:]

def rename(text, name, new):
    return re.sub(r"(?<![A-Za-z0-9_'])" + re.escape(name) + r"(?![A-Za-z0-9_(])", new, text)

scratch = os.path.join(out, ".probe")
os.makedirs(scratch)
renames = {}
for f, text in texts.items():
    want = summary(text, scratch)
    names = []
    for line in text.splitlines():
        m = re.match(r"\s*(symbols|time|unknowns)\s+(.*)", line)
        if m:
            names += re.findall(r"[A-Za-z][A-Za-z0-9_]*", m.group(2).split(">")[0])
    good = []
    for name in dict.fromkeys(names):
        if summary(rename(text, name, name + "_7"), scratch) == want:
            good.append(name)
    renames[f] = good
for root, _, fs in os.walk(scratch):
    for f in fs:
        os.remove(os.path.join(root, f))
os.rmdir(scratch)

for i in range(count):
    f = src[i % len(src)]
    text = texts[f]
    k = i // len(src)
    if renames[f] and k % 2 == 1:
        name = renames[f][(k // 2) % len(renames[f])]
        text = rename(text, name, f"{name}_{k}")
    title, _, rest = text.partition("\n")
    text = f"{title}\n% copy {i} of {f}\n{rest}"
    with open(os.path.join(out, f"h{i:04d}_{f}"), "w", encoding="utf-8") as fh:
        fh.write(text)
print(f"{count} files from {len(src)} handouts; symbols renamed where the verdicts stay: "
      + ", ".join(f"{f}: {len(r)}" for f, r in renames.items()), file=sys.stderr)
EOF

"$bin" check "$dir" | tail -1

declare -A wall cpu rss
for ((r = 0; r < runs; r++)); do
  for cores in 0 0,1; do
    stat=$( { /usr/bin/time -f '%e %U %S %M' taskset -c "$cores" "$bin" check "$dir" >/dev/null; } 2>&1 | tail -1)
    wall[$cores]+="$(echo "$stat" | awk '{print $1}') "
    cpu[$cores]+="$(echo "$stat" | awk '{printf "%.2f", $2 + $3}') "
    rss[$cores]+="$(echo "$stat" | awk '{print $4}') "
  done
done
for cores in 0 0,1; do
  w=($(printf '%s\n' ${wall[$cores]} | sort -n))
  m=($(printf '%s\n' ${rss[$cores]} | sort -n))
  printf 'taskset -c %-3s (%s worker%s): %s files, %s runs: median %s s, min %s s, max %s s; CPU (user+sys) per run %s s; peak RSS %s kB (max)\n' \
    "$cores" "$(( ${#cores} / 2 + 1 ))" "$([ "$cores" = 0 ] && echo '' || echo s)" "$files" "$runs" \
    "${w[$((runs / 2))]}" "${w[0]}" "${w[$((runs - 1))]}" "${cpu[$cores]}" "${m[$((runs - 1))]}"
done
