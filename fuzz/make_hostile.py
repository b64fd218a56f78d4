#!/usr/bin/env python3
"""Writes hostile inputs whose trouble only shows at scale (megabytes), beyond what the fuzzers
explore with their short inputs: superlinear work, loops over header counts, allocation per
claimed element. scripts/fuzz.sh runs `offsetopt check` and `offsetopt inspect` on each under a
time cap; each must end with exit 0 or 2 (never a crash or a timeout).

    python3 fuzz/make_hostile.py OUTPUT_DIR

Each file is named after what it attacks; the comment above each generator says what used to
happen (or what would happen without the limit that stops it).
"""
import os
import struct
import sys

CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_Q = [(1, 4, 3, 2), (5, 6, 7, 8), (1, 2, 6, 5), (3, 4, 8, 7), (1, 5, 8, 4), (2, 3, 7, 6)]
CUBE_T = [t for (a, b, c, d) in CUBE_Q for t in ((a, b, c), (a, c, d))]
TET_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TET_T = [(1, 3, 2), (1, 2, 4), (1, 4, 3), (2, 3, 4)]


def nested_cubes(shells=10000):
    """Concentric cubes, alternately outward and inward (a correctly nested solid with cavities).
    The nesting test is #shells x #faces of the containing shells: 15 s for this 3.8 MB file
    before the ray-test budget in validate_mesh (now: nesting left unchecked, clear message)."""
    lines = []
    for s in range(shells):
        h = shells - s
        lines += ["v %d %d %d" % ((2 * x - 1) * h, (2 * y - 1) * h, (2 * z - 1) * h) for (x, y, z) in CUBE_V]
    for s in range(shells):
        for t in CUBE_T:
            if s % 2:
                t = (t[0], t[2], t[1])
            lines.append("f %d %d %d" % tuple(i + 8 * s for i in t))
    return ("\n".join(lines) + "\n").encode()


def tets_in_big_shell(n=50000, tets=9999):
    """A bipyramid of 2n faces around 9999 small inward tetrahedra (cavities): 10^9 ray tests,
    minutes, without the budget."""
    lines = ["v 0 0 -1000000", "v 0 0 1000000"]
    # Regular n-gon approximated on an integer grid would repeat points; use a convex "staircase"
    # of distinct points on a large circle via integer arithmetic (exact in text).
    import math
    radius = 1000000
    ring = [(round(radius * math.cos(2 * math.pi * i / n)), round(radius * math.sin(2 * math.pi * i / n))) for i in range(n)]
    lines += ["v %d %d 0" % p for p in ring]
    faces = []
    for i in range(n):
        a, b = 3 + i, 3 + (i + 1) % n
        faces.append((2, a, b))   # top cone, outward
        faces.append((1, b, a))   # bottom cone, outward
    base = len(ring) + 2
    side = int(math.ceil(tets ** (1 / 3)))
    k = 0
    for i in range(side):
        for j in range(side):
            for m in range(side):
                if k == tets:
                    break
                ox, oy, oz = (i - side / 2) * 2000, (j - side / 2) * 2000, (m - side / 2) * 2000
                lines += ["v %g %g %g" % (ox + 1000 * x, oy + 1000 * y, oz + 1000 * z) for (x, y, z) in TET_V]
                faces += [(base + 4 * k + a, base + 4 * k + c, base + 4 * k + b) for (a, b, c) in TET_T]  # inward
                k += 1
    lines += ["f %d %d %d" % f for f in faces]
    return ("\n".join(lines) + "\n").encode()


def ply_empty_elements(encoding, elements=3000):
    """Elements without properties and counts at the cap: the readers looped 2^25 times per
    element (minutes for 57 KB) before they skipped property-less elements."""
    return b"ply\nformat %s 1.0\n" % encoding.encode() + b"element e 33554432\n" * elements + b"end_header\n"


def ply_binary_fans(faces=2000):
    """255-corner polygons with uchar indices: one input byte per triangle, the densest input
    there is (126 bytes of peak heap per input byte through load_mesh; proportional)."""
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex 256\nproperty float x\nproperty float y\n"
            "property float z\nelement face %d\nproperty list uchar uchar vertex_indices\nend_header\n" % faces)
    data = head.encode()
    data += b"".join(struct.pack("<3f", float(i), float(i * i % 251), float(i % 7)) for i in range(256))
    polygon = struct.pack("<B", 255) + bytes(range(255))
    return data + polygon * faces


def obj_polygons(faces=2000):
    """255-corner OBJ faces (fan-triangulated): 506,000 triangles from 1.8 MB of text."""
    lines = ["v %d %d %d" % (i, i * i % 251, i % 7) for i in range(256)]
    polygon = "f " + " ".join(str(i) for i in range(1, 256))
    return ("\n".join(lines + [polygon] * faces) + "\n").encode()


def stl_one_point(facets=400000):
    """Every corner at the same position (20 MB binary STL): welding sorts 1.2 million equal keys
    into one vertex, and the validator sees 400,000 copies of one face. Its duplicate scan walked
    back over every earlier copy for each copy (quadratic: 34 s for 200,000 copies) before the
    fix."""
    facet = struct.pack("<12f", *([0.0] * 3 + [1.0] * 9)) + b"\0\0"
    return b"one point".ljust(80, b" ") + struct.pack("<I", facets) + facet * facets


def stl_binary_header_count(count=2**25):
    """A binary STL header claiming the cap in a small file: refused from the size arithmetic."""
    return b"x" * 80 + struct.pack("<I", count) + b"\0" * 5000


def long_token_lines():
    """One 4 MB token and one line of 1,000,000 tokens: messages quote 40 characters at most."""
    return b"v " + b"1" * 4000000 + b" 0 0\n" + b"f" + b" 1" * 1000000 + b"\n"


FILES = {
    "nested_cubes.obj": nested_cubes,
    "tets_in_big_shell.obj": tets_in_big_shell,
    "ply_empty_elements_ascii.ply": lambda: ply_empty_elements("ascii"),
    "ply_empty_elements_binary.ply": lambda: ply_empty_elements("binary_big_endian"),
    "ply_binary_fans.ply": ply_binary_fans,
    "obj_polygons.obj": obj_polygons,
    "stl_one_point.stl": stl_one_point,
    "stl_binary_header_count.stl": stl_binary_header_count,
    "long_token_lines.obj": long_token_lines,
}


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_hostile.py OUTPUT_DIR")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, make in FILES.items():
        with open(os.path.join(out, name), "wb") as f:
            f.write(make())


if __name__ == "__main__":
    main()
