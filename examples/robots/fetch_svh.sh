#!/bin/sh
# Downloads SCHUNK's SVH hand as dexsuite/dex-urdf publishes it: the right hand's URDF, its
# collision meshes and the folder's licence. That licence is GPL-3.0, not a permissive one, so the
# hand is fetched on your machine rather than shipped here. The commit is pinned and each file's
# SHA-256 checked, so every fetch gives the files the README's results were measured with.
#
#   sh examples/robots/fetch_svh.sh [FOLDER]    (default: examples/robots/fetched/schunk_svh)
#
# CLASPPLAN_FETCH_BASE replaces https://raw.githubusercontent.com/dexsuite/dex-urdf/<commit>
# (a mirror, or file:///path/to/a/dex-urdf/checkout).
set -eu
commit=93505db3c0b29b4a80bd359048de7d39c9ea3218
base=${CLASPPLAN_FETCH_BASE:-https://raw.githubusercontent.com/dexsuite/dex-urdf/$commit}
out=${1:-$(dirname "$0")/fetched/schunk_svh}
command -v curl >/dev/null || { echo "fetch_svh.sh: needs curl (apt-get install curl)" >&2; exit 2; }

mkdir -p "$out/meshes/collision"
while read -r sum file; do
  if ! curl -fsL --retry 3 -o "$out/$file" "$base/robots/hands/schunk_hand/$file"; then
    echo "fetch_svh.sh: could not download $base/robots/hands/schunk_hand/$file" >&2
    exit 2
  fi
  if [ "$(sha256sum "$out/$file" | cut -d' ' -f1)" != "$sum" ]; then
    echo "fetch_svh.sh: $file differs from the file of commit $commit" >&2
    exit 2
  fi
done <<'FILES'
149795d35925f9ddb35a4270407a5dc5f839f3d29f9d929c80484981637c046a schunk_svh_hand_right.urdf
61a7eadb76f18896e20379ca6d161288d3f6c01ba128309e0ff7786d87656398 LICENSE
52808c3e08e71cfa0855389ea9dc766cc9d60f6e5a2737cf109251d627da3ea2 meshes/collision/d11.obj
1f105ba785377433f8358f944f6966c62e49701358b03bc6f2de9d958de85e85 meshes/collision/d12.obj
222d28123d15145cab9b99b1b51f57ca32b9e249d5f5c35e2b6f50bb7fc08d26 meshes/collision/d13.obj
e6dfd6157b3542f0d1c3f1e3a8b3fff6d1aca73dd0d4f64e459b74d5af3c0c75 meshes/collision/f11.obj
0518531385ebc027807240b3c1ad4f2963f01ead98b86fc0121adf519b48d1b5 meshes/collision/f12.obj
10066df55328bbde94c30cdaf6d098962ba68bc5d6e996ab07721fc5970c156f meshes/collision/f21.obj
07ac1ed0e8c6da49dad9fdbff6b0672de1cf47d9e737a18eaff5ed090f6d0a13 meshes/collision/f22_f32.obj
f47a0654479cc1b139b42f4e0e2619b66d746cac72e31984e4ac2467fb019c6e meshes/collision/f31.obj
1f86c8c614e7633cdc0e03f3dc79c0f8572e15f84326994d362115603b41a800 meshes/collision/f41.obj
ce707cc5cdbde0e0f13d4f8d47b311538e2c1f8ad237adb153aab24143b1bacd meshes/collision/f42.obj
253083989fb6824b2022c52c3089357a90657afbbea71f6e257760e2b7478a1c meshes/collision/finger_tip.obj
FILES
echo "fetched SCHUNK's SVH hand (dex-urdf $commit, GPL-3.0: $out/LICENSE) into $out"
