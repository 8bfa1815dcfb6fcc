#!/bin/sh
# Drafts the hand descriptions of this folder from the unmodified URDFs of ../example-robot-data
# with `claspplan describe`, as a user would for their own robot; nothing in them is edited by hand.
# The arms' homes are the vendors' (Franka's ready pose, Kinova's documented home); the UR5 keeps
# the draft's (every joint at 0). Run from the repository's root after building:
#   sh examples/robots/drafted/draft.sh [build/claspplan]
set -e
claspplan=${1:-build/claspplan}
robots=examples/robots/example-robot-data/robots
allegro=$robots/allegro_hand_description/urdf/allegro_right_hand.urdf
out=examples/robots/drafted
# The palm's collision box reaches 9.5 cm below palm_link's origin: each hand is mounted that far
# out from the arm's flange.
"$claspplan" describe $robots/ur_description/urdf/ur5_robot.urdf --name ur5_allegro \
  --hand-urdf $allegro --mount tool0 --mount-xyz 0,0,0.095 -o $out/ur5_allegro.yaml
"$claspplan" describe $robots/panda_description/urdf/panda.urdf --name panda_allegro \
  --hand-urdf $allegro --mount panda_link8 --mount-xyz 0,0,0.095 --replaces panda_hand \
  --home=0,-0.785398,0,-2.356194,0,1.570796,0.785398 -o $out/panda_allegro.yaml
"$claspplan" describe $robots/kinova_description/robots/kinova.urdf --name jaco_allegro \
  --hand-urdf $allegro --mount j2s6s200_end_effector --mount-xyz 0,0,0.095 \
  --replaces j2s6s200_link_finger_1 --replaces j2s6s200_link_finger_2 --mesh-hulls \
  --home 4.80,2.92,1.0,4.2,1.44,1.32 -o $out/jaco_allegro.yaml
# Romeo's left hand (one motor, LHand; every finger joint mimics it; closed at 0), cut from the
# humanoid's URDF below its wrist and turned so that its fingers point along the flange's z;
# --adaptive: its fingers follow the motor until each stops on its own at contact.
"$claspplan" describe $robots/panda_description/urdf/panda.urdf --name panda_romeo \
  --hand-urdf $robots/romeo_description/urdf/romeo.urdf --hand-urdf-root l_wrist \
  --mount panda_link8 --mount-rpy 0,-1.5707963,0 --replaces panda_hand --adaptive \
  --home=0,-0.785398,0,-2.356194,0,1.570796,0.785398 -o $out/panda_romeo.yaml
# SCHUNK's SVH hand (9 motors, 11 joints that <mimic> them, mesh and box collisions) is fetched,
# not shipped (GPL-3.0): sh examples/robots/fetch_svh.sh. Its fingers already point along the
# base's z, so it is mounted as it is.
svh=examples/robots/fetched/schunk_svh/schunk_svh_hand_right.urdf
if [ -f $svh ]; then
  "$claspplan" describe $robots/panda_description/urdf/panda.urdf --name panda_svh \
    --hand-urdf $svh --mount panda_link8 --replaces panda_hand \
    --home=0,-0.785398,0,-2.356194,0,1.570796,0.785398 -o $out/panda_svh.yaml
else
  echo "draft.sh: panda_svh skipped: run sh examples/robots/fetch_svh.sh first" >&2
fi
