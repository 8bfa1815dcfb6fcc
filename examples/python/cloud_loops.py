#!/usr/bin/env python3
"""Lists the loops of a real captured cloud (examples/clouds/table_scene_mug_stereo_textured.pcd:
a mug seen by a stereo camera) with their verdicts for the iCub hand, and draws them into
cloud_loops.png. The cloud is in its camera's frame; it is placed in the world as the scenario
examples/scenarios/clouds/table_scene_mug_stereo_textured_icub.yaml places it, and the camera's
position is its sensor origin, so that holes can be told from unseen gaps.

    PYTHONPATH=build/python python3 examples/python/cloud_loops.py [OUT.png]
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


def pose(position, rpy):
    """A 4 x 4 pose from a position and roll, pitch, yaw (URDF's fixed-axis convention)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    t = np.eye(4)
    t[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                 [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                 [-sp, cp * sr, cp * cr]]
    t[:3, 3] = position
    return t


def main(out):
    cloud = claspplan.read_cloud(os.path.join(EXAMPLES, "clouds", "table_scene_mug_stereo_textured.pcd"))
    points = cloud["points"]
    points = points[np.isfinite(points).all(axis=1)]
    camera = pose([-0.0555, 0.0714, 0.5289], [-2.148544, -0.016136, -1.560277])
    world = points @ camera[:3, :3].T + camera[:3, 3]
    found = claspplan.perceive(points=world, sensor_origin=camera[:3, 3], robot="kr5_icub",
                               crop=((0.461, -0.112, 0.003), (0.639, 0.112, 0.157)),
                               n_points=5000, d=0.02)
    print(f"{len(points)} points, beta1 = {found['beta1']}, d = {found['d']:.4f} m")
    for loop in found["loops"]:
        print(f"loop {loop['rank']}: {loop['reason']}")
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    c = found["cloud"]
    ax.scatter(c[:, 0], c[:, 1], c[:, 2], s=1, c="0.6")
    for loop in found["loops"]:
        p = np.vstack([loop["points"], loop["points"][:1]])
        ax.plot(p[:, 0], p[:, 1], p[:, 2], "r-" if loop["claspable"] else "b-", lw=2,
                label=f"{loop['rank']}: {loop['verdict']}")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.legend(fontsize=7)
    ax.set_title("stereo mug: loops for the iCub (red: claspable)")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "cloud_loops.png"))
