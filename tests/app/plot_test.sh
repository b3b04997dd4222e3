#!/usr/bin/env bash
# tools/plot draws convergence curves from stats files (here: two backends on one scene): one
# named group per run and axis, labelled axes, the runs' legends. Skips (77) without matplotlib.
#   plot_test.sh RAD SOURCE_DIR
set -euo pipefail
rad=$1 root=$2
{ /usr/bin/python3 -c 'import matplotlib' || python3 -c 'import matplotlib'; } 2>/dev/null ||
  { echo 'matplotlib is not installed: skipped'; exit 77; }
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
scene="$root/scenes/parallel_squares.des"
"$rad" -q --max-shots 5 --stats-json "$d/e.json" "$scene" "$d/e.ply"
"$rad" -q --max-shots 5 --backend grid --stats-json "$d/g.json" "$scene" "$d/g.ply"
"$root/tools/plot" "$d/p.svg" "$d/e.json" "$d/g.json"
curves=$(grep -oE 'id="run[01]-(seconds|shots)"' "$d/p.svg" | wc -l)
[ "$curves" -eq 4 ] || { echo "expected 4 named curves, found $curves"; exit 1; }
for text in 'unshot energy / emitted' '>seconds<' '>shots<' 'parallel_squares.des (grid'; do
  grep -q -- "$text" "$d/p.svg" || { echo "missing from the plot: $text"; exit 1; }
done
echo "4 curves, axes and legends drawn"
