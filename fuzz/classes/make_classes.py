#!/usr/bin/env python3
"""Writes the mesh crash classes of the reliability campaign (docs/reliability.md, "Fuzzing")
into a folder, to replay through the libFuzzer targets:

    python3 fuzz/classes/make_classes.py /tmp/classes
    fuzz/target/x86_64-unknown-linux-gnu/release/obj_mesh -timeout=10 -rss_limit_mb=2048 /tmp/classes/*.obj

The campaign's own reproducers are not kept; these rebuild each named class: a `.mtl` colour
line with fewer than three numbers (`tobj` panicked), a finite coordinate above 1e27 (the BVH
crate panicked) in OBJ, ASCII and binary PLY, and the inputs that made the BVH build quadratic
(copies of one triangle, triangles sharing a centroid, a fan, crossing slivers; 20 000 and
80 000+ of each). Only the standard library is used.
"""
import math
import struct
import sys
from pathlib import Path


def obj(tris, head=""):
    lines = [head] if head else []
    for t in tris:
        for v in t:
            lines.append("v %.9g %.9g %.9g" % v)
    for i in range(len(tris)):
        lines.append("f %d %d %d" % (3 * i + 1, 3 * i + 2, 3 * i + 3))
    return ("\n".join(lines) + "\n").encode()


def ply_ascii(tris):
    out = ["ply", "format ascii 1.0", "element vertex %d" % (3 * len(tris)),
           "property float x", "property float y", "property float z",
           "element face %d" % len(tris), "property list uchar int vertex_indices", "end_header"]
    out += ["%.9g %.9g %.9g" % v for t in tris for v in t]
    out += ["3 %d %d %d" % (3 * i, 3 * i + 1, 3 * i + 2) for i in range(len(tris))]
    return ("\n".join(out) + "\n").encode()


def ply_binary(tris):
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\n"
            "property float y\nproperty float z\nelement face %d\n"
            "property list uchar int vertex_indices\nend_header\n") % (3 * len(tris), len(tris))
    body = b"".join(struct.pack("<3f", *v) for t in tris for v in t)
    body += b"".join(struct.pack("<B3i", 3, 3 * i, 3 * i + 1, 3 * i + 2) for i in range(len(tris)))
    return head.encode() + body


def same(n):
    return [((0, 0, 0), (1, 0, 0), (0, 1, 0))] * n


def shared_centroid(n):
    out = []
    for i in range(n):
        a = 2 * math.pi * i / n
        c, s = math.cos(a), math.sin(a)
        out.append(((c, s, 0), (-0.5 * c - 0.866 * s, -0.5 * s + 0.866 * c, 0.1),
                    (-0.5 * c + 0.866 * s, -0.5 * s - 0.866 * c, -0.1)))
    return out


def fan(n):
    out = []
    for i in range(n):
        a, b = 2 * math.pi * i / n, 2 * math.pi * (i + 1) / n
        out.append(((0, 0, 0), (math.cos(a), math.sin(a), 0), (math.cos(b), math.sin(b), 0)))
    return out


def slivers(n):
    out = []
    for i in range(n):
        a = math.pi * i / n
        c, s = math.cos(a), math.sin(a)
        out.append(((-c, -s, 0), (c, s, 0), (c + 1e-4 * s, s - 1e-4 * c, 1e-4)))
    return out


def main():
    d = Path(sys.argv[1])
    d.mkdir(parents=True, exist_ok=True)
    big = ((0, 0, 3), (1, 0, 3), (0, 3e27, 3))
    files = {
        "short_kd_mtl.obj": b"mtllib a.mtl\nnewmtl a\nKd 0.5 0.5\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n",
        "short_ka_mtl.obj": b"mtllib a.mtl\nnewmtl a\nKa 1\nKs\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "huge_coordinate.obj": obj([big]),
        "huge_coordinate_ascii.ply": ply_ascii([big]),
        "huge_coordinate_binary.ply": ply_binary([big, ((1e30, 1e30, 1e30), (0, 0, 0), (1, 1, 1))]),
    }
    for n in (20_000, 86_000):
        # one face repeated (three vertices; 20 000 faces: a file of 260 kB, as the campaign's)
        files["same_face_%d.obj" % n] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n" + b"f 1 2 3\n" * n
        files["same_triangle_%d.obj" % n] = obj(same(n))
        files["same_triangle_%d.ply" % n] = ply_binary(same(n))
    for n in (20_000, 80_000):
        files["shared_centroid_%d.obj" % n] = obj(shared_centroid(n))
        files["shared_centroid_%d.ply" % n] = ply_binary(shared_centroid(n))
        files["fan_%d.obj" % n] = obj(fan(n))
        files["fan_%d.ply" % n] = ply_binary(fan(n))
        files["slivers_%d.obj" % n] = obj(slivers(n))
        files["slivers_%d.ply" % n] = ply_binary(slivers(n))
    for name, data in files.items():
        (d / name).write_bytes(data)
    print("%d files in %s" % (len(files), d))


main()
