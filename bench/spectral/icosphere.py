#!/usr/bin/env python3
"""Writes a unit icosphere (icosahedron subdivided s times, #V = 10*4^s + 2) as OBJ.

usage: icosphere.py SUBDIVISIONS OUT.obj [RADIUS]
The same construction as mesh/primitives.h make_icosphere (not bit-identical: numpy's sqrt and
ordering of midpoints may differ); the benchmark only needs a sphere of the right size.
"""
import sys

import numpy as np


def icosphere(subdivisions, radius=1.0):
    t = (1.0 + 5.0 ** 0.5) / 2.0
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    verts = [np.array(p, dtype=float) / np.linalg.norm(p) for p in v]
    for _ in range(subdivisions):
        midpoint = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                p = verts[a] + verts[b]
                verts.append(p / np.linalg.norm(p))
                midpoint[key] = len(verts) - 1
            return midpoint[key]

        g = []
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            g += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = g
    return radius * np.array(verts), np.array(f)


def write_obj(path, V, F):
    with open(path, "w") as out:
        out.write("".join("v %.17g %.17g %.17g\n" % tuple(p) for p in V))
        out.write("".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in F))


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    V, F = icosphere(int(sys.argv[1]), float(sys.argv[3]) if len(sys.argv) > 3 else 1.0)
    write_obj(sys.argv[2], V, F)
