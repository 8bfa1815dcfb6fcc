#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora (test/fuzz/corpus/<target>/): a few valid and near-valid
inputs per reader, small so that libFuzzer mutates them quickly. Deterministic; rerun after a
format change and commit the result: python3 test/fuzz/make_seeds.py"""
import math
import os
import shutil
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CORPUS = os.path.join(HERE, "corpus")

TETRA_V = [(0, 0, 0), (0.1, 0, 0), (0, 0.1, 0), (0, 0, 0.1)]
TETRA_F = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]


def write(target, name, data):
    os.makedirs(os.path.join(CORPUS, target), exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(CORPUS, target, name), "wb") as f:
        f.write(data)


def png(width, height, bit_depth, colour, rows):
    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xffffffff))
    raw = b"".join(b"\0" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" +
            chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, colour, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def depth_png():
    rows16 = [b"".join(struct.pack(">H", 0 if (u + v) % 7 == 0 else 500 + 10 * u + v)
                       for u in range(32)) for v in range(24)]
    valid = png(32, 24, 16, 0, rows16)
    write("depth_png", "valid.png", valid)
    write("depth_png", "all_zero.png", png(32, 24, 16, 0, [b"\0" * 64] * 24))
    write("depth_png", "eight_bit.png", png(32, 24, 8, 0, [bytes(range(32))] * 24))
    write("depth_png", "wrong_size.png", png(16, 16, 16, 0, [b"\1\0" * 16] * 16))
    write("depth_png", "truncated.png", valid[:len(valid) // 2])


def camera_yaml():
    good = ("width: 32\nheight: 24\nfx: 30\nfy: 30\ncx: 15.5\ncy: 11.5\ndepth_scale: 0.001\n"
            "T_world_camera:\n  - [1, 0, 0, 0.5]\n  - [0, -1, 0, 0]\n  - [0, 0, -1, 1]\n"
            "  - [0, 0, 0, 1]\n")
    write("camera_yaml", "valid.yaml", good)
    write("camera_yaml", "flat.yaml",
          "{width: 640, height: 480, fx: 525, fy: 525, cx: 319.5, cy: 239.5, depth_scale: 2e-4,"
          " T_world_camera: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}\n")
    write("camera_yaml", "missing_fx.yaml", good.replace("fx: 30\n", ""))
    write("camera_yaml", "not_rotation.yaml", good.replace("[0, -1, 0, 0]", "[0, 2, 0, 0]"))


def lzf_literals(data):
    out = b""
    for i in range(0, len(data), 32):
        block = data[i:i + 32]
        out += bytes([len(block) - 1]) + block
    return out


def pcd():
    pts = [(0.1 * i, 0.05 * i, 0.3 - 0.02 * i) for i in range(6)]
    head = ("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
            "WIDTH 6\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 6\n")
    write("pcd", "ascii.pcd", head + "DATA ascii\n" + "".join("%g %g %g\n" % p for p in pts))
    binary = b"".join(struct.pack("<fff", *p) for p in pts)
    write("pcd", "binary.pcd", (head + "DATA binary\n").encode() + binary)
    fields = b"".join(struct.pack("<" + "f" * 6, *[p[a] for p in pts]) for a in range(3))
    packed = lzf_literals(fields)
    write("pcd", "compressed.pcd", (head + "DATA binary_compressed\n").encode() +
          struct.pack("<II", len(packed), len(fields)) + packed)
    write("pcd", "organized_rgb.pcd",
          "VERSION 0.7\nFIELDS x y z rgb\nSIZE 8 8 8 4\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH 2\n"
          "HEIGHT 2\nPOINTS 4\nDATA ascii\n0 0 1 5\nnan nan nan 0\n0.1 0 1 7\n0 0.1 1 9\n")
    write("pcd", "truncated.pcd", (head + "DATA binary\n").encode() + binary[:30])
    # An organized pinhole grid with holes: enough pixels for fit_pinhole and the depth view.
    rows = []
    for v in range(12):
        for u in range(16):
            if (u * 7 + v * 3) % 11 == 0:
                rows.append("nan nan nan")
                continue
            z = 1 + 0.0625 * ((u + v) % 4)
            rows.append("%.6g %.6g %.6g" % ((u - 7.5) * z / 20, (v - 5.5) * z / 20, z))
    write("pcd", "organized_pinhole.pcd",
          "# .PCD v0.7 - an organized 16x12 pinhole grid (fx = fy = 20, cx = 7.5, cy = 5.5), "
          "NaN holes\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 16\n"
          "HEIGHT 12\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 192\nDATA ascii\n" + "\n".join(rows) + "\n")


def ply():
    v = "".join("%g %g %g\n" % p for p in TETRA_V)
    f = "".join("3 %d %d %d\n" % t for t in TETRA_F)
    props = "property float x\nproperty float y\nproperty float z\n"
    write("ply", "ascii_mesh.ply",
          "ply\nformat ascii 1.0\ncomment tetra\nelement vertex 4\n" + props +
          "element face 4\nproperty list uchar int vertex_indices\nend_header\n" + v + f)
    write("ply", "ascii_cloud.ply",
          "ply\nformat ascii 1.0\nelement vertex 4\n" + props +
          "property uchar red\nend_header\n" + "".join("%g %g %g 9\n" % p for p in TETRA_V))
    body = b"".join(struct.pack("<ddd", *p) for p in TETRA_V)
    body += b"".join(struct.pack("<Biii", 3, *t) for t in TETRA_F)
    write("ply", "binary_le_mesh.ply",
          b"ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\n"
          b"property double y\nproperty double z\nelement face 4\n"
          b"property list uchar int vertex_indices\nend_header\n" + body)
    body = b"".join(struct.pack(">fffh", *p, 3) for p in TETRA_V)
    write("ply", "binary_be_cloud.ply",
          ("ply\nformat binary_big_endian 1.0\nelement vertex 4\n" + props +
           "property short s\nend_header\n").encode() + body)


def xyz():
    write("xyz", "points.xyz", "# x y z\n0 0 0\n0.1 0 0  # a comment\n0,0.1,0\n\n0 0 0.1 7 8\n")
    write("xyz", "bad_line.xyz", "0 0 0\n0.1 0\n")


def obj():
    v = "".join("v %g %g %g\n" % p for p in TETRA_V)
    write("obj", "tetra.obj", "# tetra\no t\n" + v + "vn 0 0 1\nvt 0 0\n"
          "f 1 3 2\nf 1/1 2/1 4/1\nf 2//1 3//1 4//1\nf -4 -1 -2\n")
    write("obj", "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl m\nf 1 2 3 4\n")
    write("obj", "vertices_only.obj", v)


def stl():
    facets = ""
    for t in TETRA_F:
        facets += " facet normal 0 0 1\n  outer loop\n"
        facets += "".join("   vertex %g %g %g\n" % TETRA_V[i] for i in t)
        facets += "  endloop\n endfacet\n"
    write("stl", "ascii.stl", "solid tetra\n" + facets + "endsolid tetra\n")
    body = b"".join(struct.pack("<3f", 0, 0, 1) +
                    b"".join(struct.pack("<3f", *TETRA_V[i]) for i in t) + b"\0\0"
                    for t in TETRA_F)
    write("stl", "binary.stl", b"binary tetra".ljust(80, b" ") + struct.pack("<I", 4) + body)


def off():
    v = "".join("%g %g %g\n" % p for p in TETRA_V)
    f = "".join("3 %d %d %d\n" % t for t in TETRA_F)
    write("off", "tetra.off", "OFF\n# a tetrahedron\n4 4 6\n" + v + f)
    write("off", "one_line.off", "OFF 4 1 0\n" + v + "4 0 1 2 3\n")


def robots():
    models = os.path.join(ROOT, "robots", "models")
    shutil.copy(os.path.join(models, "kr5_sdh.urdf"), os.path.join(CORPUS, "urdf", "kr5_sdh.urdf"))
    write("urdf", "two_links.urdf",
          '<robot name="r"><link name="base_link"/><link name="a"><collision><geometry>'
          '<box size="0.1 0.1 0.1"/></geometry></collision></link>'
          '<joint name="j" type="revolute"><parent link="base_link"/><child link="a"/>'
          '<origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>'
          '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>\n')
    with open(os.path.join(models, "kr5_sdh.yaml")) as f:
        hand = f.read()
    write("hand_description", "kr5_sdh.yaml", hand)
    write("hand_description", "no_links.yaml",
          hand.replace("links: [finger_11_link, finger_12_link, finger_13_link]", "links: []"))
    write("hand_description", "short_curve.yaml",
          hand.replace("        - {link: finger_13_link}\n        - {link: finger_12_link}\n", ""))


def scenario():
    scen = os.path.join(ROOT, "examples", "scenarios")
    for name in ("purse_1_sdh.yaml", "controller_ring_sdh.yaml"):
        shutil.copy(os.path.join(scen, name), os.path.join(CORPUS, "scenario", name))
    write("scenario", "every_section.yaml",
          "robot: hand.yaml\nstart: [0, -1.5, 1.5]\nobject:\n"
          "  depth:\n    - {image: a.png, camera: a.yaml}\n"
          "environment: {boxes: [{size: [1, 1, 0.1], position: [0, 0, 0], rpy: [0, 0, 1]}]}\n"
          "clasp: {near: [0.5, 0, 0.2], targets: 12}\n"
          "perception: {points: 500, d: 0, d_factor: 3.5, min_hole: 0.03, seed: 2,"
          " remove_plane: false, workspace: {min: [0, -1, 0], max: [1, 1, 1]}}\n"
          "controller: {gain_distance: 0.02, dt: 1.0, max_steps: 100}\n"
          "planner: {max_cycles: 10, time_limit: 0, sample_min: [0, -1, 0],"
          " sample_max: [1, 1, 1], verify_in_search: false}\nseed: 3\n")
    write("scenario", "container.yaml",
          "robot: kr5_dlr\nobject:\n  shape: {type: container, radius: 0.05, height: 0.15,"
          " wall: 0.004, handle_radius: 0.03, handle_tube: 0.006}\n  views: [[0, 0, 1]]\n"
          "  noise: {sigma: 0.001, dropout: 0.1}\n")


def curve():
    ring = "".join("%.6f %.6f 0\n" % (0.1 * math.cos(2 * math.pi * k / 12),
                                     0.1 * math.sin(2 * math.pi * k / 12)) for k in range(12))
    write("curve", "ring.xyz", "# a closed ring\n" + ring)
    write("curve", "open.xyz", "0 0 0\n0 0 0.1\n0.05 0 0.15\n")
    write("curve", "repeated_end.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 0\n")


def result_json():
    ring = ", ".join("[%.4f, %.4f, 0.2]" % (0.5 + 0.1 * math.cos(2 * math.pi * k / 8),
                                             0.1 * math.sin(2 * math.pi * k / 8))
                     for k in range(8))
    q = "[0, -1.5707963, 1.5707963, 0, 1.5707963, 0, -1, 1, -1, 1, -1, 1]"
    write("result_json", "minimal.json",
          '{"robot": "kr5_sdh", "seed": 4, "final_q": %s, "loop": [%s],\n'
          ' "object_mesh": {"vertices": [[0.5, 0, 0], [0.6, 0, 0], [0.5, 0.1, 0], [0.5, 0, 0.1]],'
          ' "triangles": [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]},\n'
          ' "environment": {"boxes": [{"size": [2, 2, 0.05], "position": [0.5, 0, -0.025],'
          ' "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}]},\n'
          ' "waypoints": [%s, %s]}\n' % (q, ring, q, q))
    write("result_json", "short_q.json",
          '{"robot": "kr5_sdh", "final_q": [0, 1], "loop": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],'
          ' "object_mesh": {"vertices": [], "triangles": []}}\n')


if __name__ == "__main__":
    shutil.rmtree(CORPUS, ignore_errors=True)
    os.makedirs(os.path.join(CORPUS, "urdf"))
    os.makedirs(os.path.join(CORPUS, "scenario"))
    for make in (depth_png, camera_yaml, pcd, ply, xyz, obj, stl, off, robots, scenario, curve,
                 result_json):
        make()
