#!/usr/bin/env python3
"""Plans a clasp of the bag (examples/depth/bag_2, two rendered depth views) with the SDH hand,
then draws the object's points, the clasped loop and the closed hand's finger curves, and the
joints along the path, into plan_from_depth.png.

    PYTHONPATH=build/python python3 examples/python/plan_from_depth.py [OUT.png]
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import claspplan  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.dirname(HERE)


def main(out):
    scenario = os.path.join(EXAMPLES, "scenarios", "bag_2_sdh.yaml")
    result = claspplan.run(scenario, seed=1, max_cycles=200)
    print(f"verified: {result['verified']}  {result['reason']}")
    robot = claspplan.Robot("kr5_sdh")
    # The object as perception saw it, from the same depth files as arrays.
    views = [claspplan.read_depth(os.path.join(EXAMPLES, "depth", "bag_2", f"view_{i}.png"),
                                  os.path.join(EXAMPLES, "depth", "bag_2", f"view_{i}.yaml"))
             for i in range(2)]
    seen = claspplan.perceive(depth=[v[:3] for v in views], robot=robot,
                              crop=((0.2, -0.4, 0.01), (0.95, 0.4, 0.7)),
                              no_reading_is_free=views[0][3])
    fig = plt.figure(figsize=(11, 5))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    cloud = seen["cloud"]
    ax.scatter(cloud[:, 0], cloud[:, 1], cloud[:, 2], s=1, c="0.6")
    loop = result["loop"]
    if len(loop):
        closed = np.vstack([loop, loop[:1]])
        ax.plot(closed[:, 0], closed[:, 1], closed[:, 2], "r-", lw=2, label="clasped loop")
    if len(result["final_q"]):
        for k, curve in enumerate(robot.finger_curves(result["final_q"])):
            ax.plot(curve[:, 0], curve[:, 1], curve[:, 2], "b-", lw=1.5,
                    label="finger curves" if k == 0 else None)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.legend(loc="upper left")
    ax.set_title(f"bag_2, SDH: {'verified' if result['verified'] else 'no clasp'}")
    ax2 = fig.add_subplot(1, 2, 2)
    path = result["path"]
    for j in range(robot.arm_dof):
        ax2.plot(path[:, j], label=robot.joint_names[j])
    ax2.set_xlabel("waypoint")
    ax2.set_ylabel("joint (rad)")
    ax2.set_title("arm joints along the path")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")
    return 0 if result["verified"] else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "plan_from_depth.png"))
