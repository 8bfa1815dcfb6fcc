#!/bin/sh
# Draws docs/results.md's pictures of the paper's objects: `claspplan loops --png` of each object's
# pose 1 from its committed depth files (K_d, the best-ranked loop in red, the other stable loops
# in blue), written to examples/pictures/paper/<object>.png (docs/results.md shows them 300 pixels wide).
# Usage: examples/scripts/paper_pictures.sh [path/to/claspplan]
set -e
here=$(cd "$(dirname "$0")/.." && pwd)
exe=${1:-$here/../build/claspplan}
out="$here/pictures/paper"
mkdir -p "$out"
for object in purse bag travelbag lawnmower chair; do
  d="$here/depth/${object}_1"
  crop=$(python3 -c "import json,sys; w=json.load(open(sys.argv[1]))['workspace']; \
print(','.join(str(x) for x in w['min'] + w['max']))" "$d/scene.json")
  "$exe" loops "$d/view_0.png" --camera "$d/view_0.yaml" "$d/view_1.png" --camera "$d/view_1.yaml" \
    --crop="$crop" --png "$out/$object.png" >/dev/null 2>&1
  echo "$out/$object.png"
done
