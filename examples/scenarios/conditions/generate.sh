#!/usr/bin/env bash
# Writes the "conditions" scenarios: some of the real meshes of examples/meshes/ (and the procedural
# jug) under conditions users meet: turned to four yaws, standing on a table 10-20 cm high (an
# environment box, known to the planner), with a second object beside them (a clutter box the
# synthetic cameras render but the planner is not told of: it must learn it from depth), seen by the
# three synthetic depth cameras of real/generate.sh (1 mm noise), once per hand.
# Run from anywhere; it rewrites <object>_yaw<deg>_<hand>.yaml beside itself.
set -euo pipefail
cd "$(dirname "$0")"

# name  object (mesh file or "jug")  reference yaw (rad; yaw<deg> turns the object from it)
#       half-extents in x and y of the object in its own frame (m; for the clutter and the crop)
#       what it is
objects=(
  "pitcher       pitcher_ycb019            0.7853982  0.076 0.076  pitcher: a handle, a wide mouth and a spout (at yaw0 the handle to +y, as in real/)"
  "spice_rack    spice_rack_aws            0          0.026 0.147  wire spice rack with three jars and three empty rings"
  "utensil_rail  kitchen_utensil_rail_aws  0          0.037 0.219  wall rail with a whisk (wire loops), ladle and spatulas"
  "clamp_large   clamp_large_ycb051        0          0.061 0.087  spring clamp lying flat: its opening faces the table"
  "cup           plastic_cup_gazebo_neg    0          0.038 0.038  negative: open plastic cup (a mouth, no handle)"
  "bowl          bowl_ycb024_neg           0          0.082 0.082  negative: bowl"
  "trash_bin     trash_bin_aws_neg         0          0.143 0.142  negative: open bin with a rim ring on its wall"
  "jug           jug                       1.5707963  0.140 0.080  procedural jug: an open container with a side handle (at yaw0 the handle to +y, as jug_<hand>)"
)
hands=(sdh dlr icub armar3)
# yaw (deg)  table height (m)  side of the second object (+x: behind the object, away from the
# robot; +y / -y: to the robot's left / right)
conditions=(
  "0    0.10  +x"
  "90   0.13  +y"
  "180  0.16  -y"
  "270  0.20  +x"
)
gap=0.06           # between the object's bounding box and the second object
clutter_size=(0.08 0.15 0.20)   # thin side towards the object

# Where HOME (the hand pointing down) puts a hand into the object, that hand starts with the arm
# raised, as the paper's bag scenarios do: the DLR's fingers at HOME are in the jug's mouth, 0.42 m
# high, and the fingers of every hand but the iCub in the utensil rail turned along x. Elsewhere it
# starts at HOME.
raised_start=(jug_yaw270_dlr
              utensil_rail_yaw90_sdh utensil_rail_yaw90_dlr utensil_rail_yaw90_armar3
              utensil_rail_yaw270_sdh utensil_rail_yaw270_dlr utensil_rail_yaw270_armar3)
home_start="[0, -1.5707963, 1.5707963, 0, 1.5707963, 0]  # arm: HOME with the hand pointing down"
raised="[0, -1.9, 1.5707963, 0, 1.9, 0]  # arm: the hand pointing down, raised above the object"

calc() { awk "BEGIN { printf \"%.4f\", $1 }"; }

count=0
for entry in "${objects[@]}"; do
  read -r name mesh yaw0 ex ey what <<<"$entry"
  if [[ $mesh == jug ]]; then
    object_lines="  shape: {type: container, radius: 0.06, height: 0.22, wall: 0.004, handle_radius: 0.075,
          handle_tube: 0.01}"
  else
    object_lines="  mesh: ../../meshes/${mesh}.obj"
  fi
  for cond in "${conditions[@]}"; do
    read -r deg table side <<<"$cond"
    yaw=$(awk "BEGIN { printf \"%.7f\", $yaw0 + $deg * 3.14159265358979 / 180 }")
    # the object's bounding box in the world, turned by yaw (half-extents hx, hy about (0.55, 0))
    hx=$(calc "(c = cos($yaw)) * 0 + (c < 0 ? -c : c) * $ex + ((s = sin($yaw)) < 0 ? -s : s) * $ey")
    hy=$(calc "(c = cos($yaw)) * 0 + ((s = sin($yaw)) < 0 ? -s : s) * $ex + (c < 0 ? -c : c) * $ey")
    case $side in
      +x) cx=$(calc "0.55 + $hx + $gap + ${clutter_size[0]} / 2"); cy=0
          csize="[${clutter_size[0]}, ${clutter_size[1]}, ${clutter_size[2]}]"
          where="behind the object" ;;
      +y) cx=0.55; cy=$(calc "$hy + $gap + ${clutter_size[0]} / 2")
          csize="[${clutter_size[1]}, ${clutter_size[0]}, ${clutter_size[2]}]"
          where="to the object's left (+y)" ;;
      -y) cx=0.55; cy=$(calc "-($hy + $gap + ${clutter_size[0]} / 2)")
          csize="[${clutter_size[1]}, ${clutter_size[0]}, ${clutter_size[2]}]"
          where="to the object's right (-y)" ;;
    esac
    cz=$(calc "$table + ${clutter_size[2]} / 2")
    tz=$(calc "$table / 2")
    target_z=$(calc "$table + 0.15")
    # the crop: above the table, the object's box grown by 22 cm (the second object included)
    wx0=$(calc "0.55 - $hx - 0.22"); wx1=$(calc "0.55 + $hx + 0.22")
    wy0=$(calc "-$hy - 0.22"); wy1=$(calc "$hy + 0.22")
    wz0=$(calc "$table + 0.003"); wz1=$(calc "$table + 0.5")
    for hand in "${hands[@]}"; do
      start=$home_start
      for r in "${raised_start[@]}"; do [[ $r == "${name}_yaw${deg}_${hand}" ]] && start=$raised; done
      cat >"${name}_yaw${deg}_${hand}.yaml" <<YAML
# ${what}. Generated by generate.sh: do not edit; rerun the script.
# Turned ${deg} deg from its reference pose, on a table ${table} m high (an environment box), with a
# second object (a ${clutter_size[0]} x ${clutter_size[1]} x ${clutter_size[2]} m box the planner is not told of) ${gap} m ${where},
# seen by three synthetic depth cameras (1 mm noise) as in real/: two above the robot's shoulders,
# one from behind.
name: ${name}_yaw${deg}_${hand}
robot: kr5_${hand}
start: ${start}
object:
${object_lines}
  pose: {position: [0.55, 0, ${table}], rpy: [0, 0, ${yaw}]}
  cameras:
    - {position: [0.2, -0.6, 0.85], target: [0.55, 0, ${target_z}]}
    - {position: [0.2, 0.6, 0.85], target: [0.55, 0, ${target_z}]}
    - {position: [1.0, 0, 0.85], target: [0.55, 0, ${target_z}]}  # behind: the space beyond bars
  noise: {sigma: 0.001}
  clutter:
    - {size: ${csize}, position: [${cx}, ${cy}, ${cz}]}  # a second object, ${where}
environment:
  boxes:
    - {size: [2.0, 2.0, 0.05], position: [0.5, 0, -0.025]}  # the floor
    - {size: [0.8, 1.0, ${table}], position: [0.6, 0, ${tz}]}  # the table
perception:
  workspace: {min: [${wx0}, ${wy0}, ${wz0}], max: [${wx1}, ${wy1}, ${wz1}]}
seed: 1
YAML
      count=$((count + 1))
    done
  done
done
echo "wrote ${count} scenarios"
