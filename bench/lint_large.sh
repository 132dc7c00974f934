#!/usr/bin/env bash
# Times `rigor lint` on three generated 10 MB Markdown documents (issue #18: a 10 MB
# document is linted in well under a second):
#   prose  — lecture notes as they are: mostly prose, with the equations of our own
#            notes (tests/lint/handout_notes.md) once in every ~100 KB section;
#   dense  — those notes themselves repeated until 10 MB (every display math block kept);
#   unread — 10 MB of displays rigor cannot read (`\foo`, `\begin{tikzpicture}`): each
#            is a needs-context finding, and reporting them must stay linear.
# Usage: bench/lint_large.sh [runs]   (needs a release build: cargo build --release)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
notes=tests/lint/handout_notes.md
bin=target/$(rustc -vV | sed -n 's/^host: //p')/release/rigor
[ -x "$bin" ] || cargo build --release --quiet
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
python3 - "$notes" "$dir" <<'PY'
import sys
notes, out = open(sys.argv[1]).read(), sys.argv[2]
target = 9_900_000  # just under the 10 MB (10,000,000-byte) file limit
filler = ("The moment of inertia depends on how the mass is spread about the axis; "
          "a body with its mass far from the axis resists angular acceleration more. ") * 12
with open(f"{out}/prose.md", "w") as f:
    size, k = 0, 0
    while True:
        part = f"\n\n## Section {k}\n\n" + (filler + "\n\n") * 60
        if k % 1 == 0:
            part += notes
        if size + len(part) > target: break
        f.write(part); size += len(part); k += 1
with open(f"{out}/unread.md", "w") as f:
    part = "Some prose. $$ \\foo{x} = \\begin{tikzpicture} $$\n\n"
    f.write(part * (target // len(part)))
with open(f"{out}/dense.md", "w") as f:
    size, k = 0, 0
    while True:
        part = f"\n\n# Copy {k}\n\n" + notes
        if size + len(part) > target: break
        f.write(part); size += len(part); k += 1
PY
for doc in unread prose dense; do
  ls -l "$dir/$doc.md" | awk '{printf "%s: %.1f MB, ", $NF, $5/1048576}'
  "$bin" lint "$dir/$doc.md" | tail -1
  times=()
  for _ in $(seq "$runs"); do
    s=$(date +%s.%N); "$bin" lint "$dir/$doc.md" > /dev/null 2>&1 || true; e=$(date +%s.%N)
    times+=("$(echo "$e - $s" | bc)")
  done
  printf '%s\n' "${times[@]}" | sort -n | awk -v d="$doc" '{a[NR]=$1} END {printf "%s: median %.2f s over %d runs\n", d, a[int((NR+1)/2)], NR}'
done
