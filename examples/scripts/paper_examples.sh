#!/bin/sh
# Regenerates the paper's example depth files (examples/depth/<scene>/) with the synthetic depth
# sensor and the scenarios that read them (examples/scenarios/<object>_<pose>_<hand>.yaml,
# chair_obstructed_<hand>.yaml), then the pictures of the objects in docs/results.md (paper_pictures.sh).
# Usage: examples/scripts/paper_examples.sh [path/to/claspplan]
set -e
here=$(cd "$(dirname "$0")/.." && pwd)
exe=${1:-$here/../build/claspplan}
rm -rf "$here/depth"
"$exe" render-paper "$here/depth" --noise 0.001 --dropout 0.02
python3 "$here/scripts/paper_scenarios.py"
"$here/scripts/paper_pictures.sh" "$exe"
du -sh "$here/depth"
