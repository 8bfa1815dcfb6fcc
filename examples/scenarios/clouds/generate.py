#!/usr/bin/env python3
"""Writes examples/scenarios/clouds/<cloud>_<hand>.yaml: each real captured cloud of
examples/clouds/ (organized PCDs from the PCL data repository, BSD 3-clause, in their camera's
frame) placed in front of the KR5 as a depth view of its own camera, for the iCub and SDH hands.

For each cloud the camera's pose in the world (REP 103, world = base_link) is chosen so that
  - the table (the cloud's dominant plane) is horizontal, its normal along +z, at z = TABLE_Z;
  - the camera's viewing direction, projected on the table, points along +x (the robot looks
    the way the camera did);
  - the objects on the table (the points 1-40 cm above it within AXIS_RADIUS of the camera's
    optical axis) are centred at (OBJECT_X, 0, TABLE_Z).
The table plane in the camera frame is `claspplan loops <cloud> --json`'s `support_plane` when the
program reports one; it does not when the cloud's table is tilted in its own frame (the plane
removal takes only near-horizontal planes), and then this script fits it itself (a seeded RANSAC
and a least-squares refinement on every 4th pixel of every 4th row). Python 3 standard library only;
the output is the same byte for byte on every run.

Usage: examples/scenarios/clouds/generate.py [path/to/claspplan]   (default: build/claspplan)
"""
import json
import math
import os
import random
import struct
import subprocess
import sys
import textwrap

HERE = os.path.dirname(os.path.abspath(__file__))
CLOUDS = os.path.join(HERE, "..", "..", "clouds")
TABLE_Z = 0.0  # the table top: the floor of the other scenarios, which the KR5 reaches well
OBJECT_X = 0.55  # where the paper and real scenarios put their objects
AXIS_RADIUS = 0.5  # objects: points within this distance of the camera's optical axis
MARGIN = 0.05  # around the objects, for the workspace crop
POINTS = 5000  # K_d's points over the crop: a 3 cm handle keeps several across its bar
HANDS = [("icub", "kr5_icub"), ("sdh", "kr5_sdh")]
# K_d's edge bound where the automatic one (3.5 x the mean spacing, 5 mm here) is too fine: the
# stereo mug's handle meets the body across a 1.5-2 cm gap in the data (no reading where the handle
# joins the body), so its ring closes only at d = 2 cm.
D = {"table_scene_mug_stereo_textured": (0.02, "the handle's ring closes across a 1.5-2 cm gap "
                                               "in the stereo data only at d = 2 cm")}
START = "[0, -1.5707963, 1.5707963, 0, 1.5707963, 0]"  # examples/scenarios/real: HOME, hand down

# What each file shows (examples/clouds/README.md, ../shared/real_clouds/README.md).
SCENES = {
    "table_scene_mug_stereo_textured": (
        "stereo camera: one mug on a table, its handle to the camera's side, about 0.9 m away; "
        "the handle's hole (about 3 cm) is a loop for the iCub's fingers, too narrow for the SDH; "
        "the mouth is a container's mouth, never a handle"),
    "milk_cartoon_all_small_clorox": (
        "Kinect: a milk carton, a bottle and small objects on a table; no through-hole anywhere: "
        "every loop is a gap or an occlusion shadow"),
    "osd_learn0": "Kinect: stacked cereal boxes; no handle: gaps between boxes and their shadows",
    "osd_learn8": "Kinect: stacked cereal boxes; no handle: gaps between boxes and their shadows",
    "osd_learn16": (
        "Kinect: a box lying across two others; the only real through-gap in this set is under "
        "the bridging box; shadows beside it are not holes"),
    "osd_learn30": "Kinect: a box on a can lying on its side; no handle",
    "osd_learn34": (
        "Kinect: bowls, a plastic pot with two small side handles, a round tin, small jars; rims "
        "are mouths, the pot's handle holes (1-2 cm) are narrower than any finger"),
    "osd_learn36": (
        "Kinect: bowls, a plastic pot with two small side handles, a round tin, small jars; rims "
        "are mouths, the pot's handle holes (1-2 cm) are narrower than any finger"),
    "osd_learn38": (
        "Kinect: bowls, a plastic pot with two small side handles, a round tin, small jars; rims "
        "are mouths, the pot's handle holes (1-2 cm) are narrower than any finger"),
    "osd_learn40": (
        "Kinect: bowls, a plastic pot with two small side handles, a round tin, small jars; rims "
        "are mouths, the pot's handle holes (1-2 cm) are narrower than any finger"),
    "osd_learn44": (
        "Kinect: a mug, a crisps tube and a round tin, about 1 m away; the mug's handle covers a "
        "few pixels: not enough to clasp"),
}


# ---- PCD reading (organized, DATA binary_compressed or binary) ---------------------------------

def lzf_decompress(data, size):
    out = bytearray()
    i, n = 0, len(data)
    while i < n:
        ctrl = data[i]
        i += 1
        if ctrl < 32:  # literal run of ctrl + 1 bytes
            out += data[i:i + ctrl + 1]
            i += ctrl + 1
            continue
        length = ctrl >> 5
        if length == 7:
            length += data[i]
            i += 1
        ref = len(out) - ((ctrl & 0x1F) << 8) - data[i] - 1
        i += 1
        length += 2
        if ref + length <= len(out):
            out += out[ref:ref + length]
        else:  # overlapping: repeat byte by byte
            for k in range(length):
                out.append(out[ref + k])
    if len(out) != size:
        raise ValueError("LZF: %d bytes, expected %d" % (len(out), size))
    return bytes(out)


def read_pcd(path):
    """(width, height, viewpoint [tx ty tz qw qx qy qz], xs, ys, zs) of an organized PCD."""
    with open(path, "rb") as f:
        blob = f.read()
    header, pos = {}, 0
    while True:
        end = blob.index(b"\n", pos)
        line = blob[pos:end].decode("ascii").strip()
        pos = end + 1
        if not line or line.startswith("#"):
            continue
        key, _, value = line.partition(" ")
        header[key] = value.split()
        if key == "DATA":
            break
    fields, sizes, types = header["FIELDS"], [int(s) for s in header["SIZE"]], header["TYPE"]
    counts = [int(c) for c in header.get("COUNT", ["1"] * len(fields))]
    width, height = int(header["WIDTH"][0]), int(header["HEIGHT"][0])
    n = width * height
    viewpoint = [float(v) for v in header.get("VIEWPOINT", "0 0 0 1 0 0 0".split())]
    kind = header["DATA"][0]
    columns = {}
    if kind == "binary_compressed":
        packed, unpacked = struct.unpack_from("<II", blob, pos)
        raw = lzf_decompress(blob[pos + 8:pos + 8 + packed], unpacked)
        offset = 0
        for name, size, count in zip(fields, sizes, counts):
            if name in ("x", "y", "z"):
                columns[name] = struct.unpack_from("<%df" % n, raw, offset)
            offset += size * count * n
    elif kind == "binary":
        stride = sum(s * c for s, c in zip(sizes, counts))
        offset = 0
        for name, size, count in zip(fields, sizes, counts):
            if name in ("x", "y", "z"):
                columns[name] = [struct.unpack_from("<f", blob, pos + k * stride + offset)[0]
                                 for k in range(n)]
            offset += size * count
    else:
        raise ValueError(path + ": DATA " + kind + " not supported here")
    return width, height, viewpoint, columns["x"], columns["y"], columns["z"]


# ---- small vector algebra ---------------------------------------------------------------------

def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def unit(a):
    n = math.sqrt(dot(a, a))
    return [a[0] / n, a[1] / n, a[2] / n]


def smallest_eigenvector(m):
    """Of a symmetric 3x3 matrix, by Jacobi rotations."""
    a = [row[:] for row in m]
    v = [[1.0 if i == j else 0.0 for j in range(3)] for i in range(3)]
    for _ in range(50):
        p, q = max(((0, 1), (0, 2), (1, 2)), key=lambda pq: abs(a[pq[0]][pq[1]]))
        if abs(a[p][q]) < 1e-15:
            break
        theta = 0.5 * math.atan2(2 * a[p][q], a[q][q] - a[p][p])
        c, s = math.cos(theta), math.sin(theta)
        for k in range(3):  # A <- A J
            akp, akq = a[k][p], a[k][q]
            a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
        for k in range(3):  # A <- J^T A
            apk, aqk = a[p][k], a[q][k]
            a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
        for k in range(3):
            vkp, vkq = v[k][p], v[k][q]
            v[k][p], v[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    i = min(range(3), key=lambda j: a[j][j])
    return [v[0][i], v[1][i], v[2][i]]


def fit_plane(points, seed=1, iterations=300, tolerance=0.01):
    """The dominant plane [a, b, c, d] (unit normal): seeded RANSAC, then least squares."""
    rng = random.Random(seed)
    best, best_count = None, -1
    for _ in range(iterations):
        p, q, r = rng.sample(points, 3)
        nrm = cross(sub(q, p), sub(r, p))
        if dot(nrm, nrm) < 1e-12:
            continue
        nrm = unit(nrm)
        d = -dot(nrm, p)
        count = sum(1 for x in points if abs(dot(nrm, x) + d) < tolerance)
        if count > best_count:
            best, best_count = (nrm, d), count
    nrm, d = best
    for tol in (tolerance, 0.006):
        inliers = [x for x in points if abs(dot(nrm, x) + d) < tol]
        c = [sum(x[k] for x in inliers) / len(inliers) for k in range(3)]
        cov = [[sum((x[i] - c[i]) * (x[j] - c[j]) for x in inliers) for j in range(3)]
               for i in range(3)]
        new = smallest_eigenvector(cov)
        if dot(new, nrm) < 0:
            new = [-v for v in new]
        nrm, d = unit(new), -dot(unit(new), c)
    return [nrm[0], nrm[1], nrm[2], d]


def rpy_of(r):
    """URDF roll, pitch, yaw of a rotation matrix R = Rz(yaw) Ry(pitch) Rx(roll)."""
    pitch = math.asin(max(-1.0, min(1.0, -r[2][0])))
    roll = math.atan2(r[2][1], r[2][2])
    yaw = math.atan2(r[1][0], r[0][0])
    return roll, pitch, yaw


def percentile(values, f):
    s = sorted(values)
    return s[min(len(s) - 1, max(0, int(round(f * (len(s) - 1)))))]


def num(x, digits=4):
    s = "%.*f" % (digits, x)
    return "0" if float(s) == 0 else s.rstrip("0").rstrip(".")


def vec(v, digits=4):
    return "[" + ", ".join(num(x, digits) for x in v) + "]"


# ---- per cloud --------------------------------------------------------------------------------

def place(name, exe):
    path = os.path.join(CLOUDS, name + ".pcd")
    width, height, viewpoint, xs, ys, zs = read_pcd(path)
    points = []
    for row in range(0, height, 4):
        for col in range(0, width, 4):
            k = row * width + col
            p = (xs[k], ys[k], zs[k])
            if all(math.isfinite(v) for v in p):
                points.append(p)
    camera = viewpoint[:3]  # the sensor's origin in the cloud's frame (0 0 0 in every file here)
    plane, source = None, "fitted by generate.py (claspplan loops reports no support_plane)"
    try:
        out = subprocess.run([exe, "loops", path, "--json"], check=True, capture_output=True,
                             text=True).stdout
        reported = json.loads(out).get("support_plane")
        if reported:
            length = math.sqrt(dot(reported, reported))
            plane = [v / length for v in reported]
            source = "claspplan loops --json's support_plane"
    except (OSError, subprocess.CalledProcessError) as e:
        sys.exit("generate.py: %s loops %s failed: %s" % (exe, path, e))
    if plane is None:
        plane = fit_plane(points)
    up = plane[:3]
    if dot(up, camera) + plane[3] < 0:  # the normal towards the camera, the objects' side
        up, plane = [-v for v in up], [-v for v in plane]
    # The optical axis: +z of the cloud's frame, or -z where the points lie behind (milk scene).
    zs_valid = sorted(p[2] for p in points)
    axis = [0.0, 0.0, 1.0 if zs_valid[len(zs_valid) // 2] > 0 else -1.0]
    forward = unit(sub(axis, [dot(axis, up) * u for u in up]))
    left = cross(up, forward)
    rot = [forward, left, up]  # rows: the world axes in the cloud's frame; world = rot * p + t
    objects = []
    for p in points:
        h = dot(up, p) + plane[3]
        if not 0.01 < h < 0.4:
            continue
        rel = sub(p, camera)
        along = dot(rel, axis)
        off = sub(rel, [along * a for a in axis])
        if along > 0 and dot(off, off) < AXIS_RADIUS ** 2:
            objects.append((dot(forward, p), dot(left, p), h))
    if len(objects) < 50:
        sys.exit("generate.py: %s: only %d points above the table" % (name, len(objects)))
    lo = [percentile([o[k] for o in objects], 0.02) for k in range(3)]
    hi = [percentile([o[k] for o in objects], 0.98) for k in range(3)]
    centre = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2]
    t = [OBJECT_X - centre[0], -centre[1], TABLE_Z + plane[3]]
    roll, pitch, yaw = rpy_of(rot)
    world_lo = [lo[0] + t[0] - MARGIN, lo[1] + t[1] - MARGIN, TABLE_Z + 0.003]
    world_hi = [hi[0] + t[0] + MARGIN, hi[1] + t[1] + MARGIN, TABLE_Z + hi[2] + MARGIN]
    return {
        "position": t, "rpy": [roll, pitch, yaw], "plane": plane, "source": source,
        "camera_world": [dot(rot[i], camera) + t[i] for i in range(3)],
        "tilt": math.degrees(math.acos(max(-1.0, min(1.0, abs(dot(axis, up)))))),
        "min": world_lo, "max": world_hi, "objects": len(objects),
    }


def write(name, hand, robot, p):
    text = (
        "Real captured cloud %s.pcd (%s). Data: the Point Cloud Library's data repository "
        "(github.com/PointCloudLibrary/data), BSD 3-clause, Copyright (c) 2013, Point Cloud "
        "Library (PCL); see ../../clouds/README.md. Generated by generate.py: the cloud as a depth "
        "view of its own camera, placed so that the table (plane %s in the camera frame, %s) is "
        "horizontal at z = %s, the camera looks along +x (from %s, %.0f degrees below the "
        "horizon) and the objects are centred at (%s, 0); the table is a box, the workspace "
        "crops to the region above it around the objects."
        % (name, SCENES[name], vec(p["plane"]), p["source"], num(TABLE_Z),
           vec(p["camera_world"], 3), 90 - p["tilt"], num(OBJECT_X)))
    lines = ["# " + line for line in textwrap.wrap(text, 98)]
    lines += [
        "name: clouds_%s_%s" % (name, hand),
        "robot: " + robot,
        "start: %s  # arm: HOME with the hand pointing down" % START,
        "object:",
        "  cloud:",
        "    - file: ../../clouds/%s.pcd" % name,
        "      pose: {position: %s, rpy: %s}  # the camera in the world"
        % (vec(p["position"]), vec(p["rpy"], 6)),
        "environment:",
        "  boxes:",
        "    - {size: [2.0, 2.0, 0.05], position: [0.5, 0, %s]}  # the table" % num(TABLE_Z - 0.025),
        "perception:",
        "  points: %d" % POINTS,
    ]
    if name in D:
        lines.append("  d: %s  # %s" % (num(D[name][0]), D[name][1]))
    lines += [
        "  workspace: {min: %s, max: %s}" % (vec(p["min"], 3), vec(p["max"], 3)),
        "seed: 1",
    ]
    with open(os.path.join(HERE, "%s_%s.yaml" % (name, hand)), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    exe = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "..", "..", "build",
                                                              "claspplan")
    for name in sorted(SCENES):
        p = place(name, exe)
        for hand, robot in HANDS:
            write(name, hand, robot, p)
        print("%s: camera at %s, %d object points, workspace %s .. %s" %
              (name, vec(p["camera_world"], 3), p["objects"], vec(p["min"], 3),
               vec(p["max"], 3)))


if __name__ == "__main__":
    main()
