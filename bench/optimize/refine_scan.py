#!/usr/bin/python3
"""Refines a real triangle mesh to at least N vertices without moving its surface, for the scale
benchmark of issue 22 (a scan of 10^6 vertices when ../shared has none that large).

Midpoint (1-to-4) subdivision while a whole step stays below N, then red-green refinement of the
faces lowest in z: those faces are split 1-to-4, their neighbours across a split edge in two or
three, so the mesh stays closed and manifold and every vertex lies on the input's surface. The
lowest faces are chosen so that N is met with the fewest new vertices; the count is bisected.

usage: /usr/bin/python3 bench/optimize/refine_scan.py MESH.ply|MESH.obj OUT.obj [--vertices N]
Reads binary or ASCII PLY (float or double coordinates, extra face properties skipped) and OBJ.
"""
import argparse
import sys

import numpy as np

PLY_TYPES = {'char': 'i1', 'uchar': 'u1', 'short': 'i2', 'ushort': 'u2', 'int': 'i4', 'uint': 'u4',
             'float': 'f4', 'double': 'f8', 'int8': 'i1', 'uint8': 'u1', 'int32': 'i4', 'uint32': 'u4',
             'float32': 'f4', 'float64': 'f8'}


def read_ply(path):
    data = open(path, 'rb').read()
    end = data.index(b'end_header') + len(b'end_header')
    end = data.index(b'\n', end) + 1
    lines = data[:end].decode('ascii', 'replace').splitlines()
    fmt, elements = 'ascii', []
    for line in lines:
        w = line.split()
        if not w:
            continue
        if w[0] == 'format':
            fmt = w[1]
        elif w[0] == 'element':
            elements.append([w[1], int(w[2]), []])
        elif w[0] == 'property':
            elements[-1][2].append(w[1:])
    if fmt == 'ascii':
        tokens = data[end:].split()
        at, V, F = 0, None, None
        for name, count, props in elements:
            rows = []
            for _ in range(count):
                row = []
                for p in props:
                    if p[0] == 'list':
                        n = int(tokens[at]); at += 1
                        row.append([int(t) for t in tokens[at:at + n]]); at += n
                    else:
                        row.append(float(tokens[at])); at += 1
                rows.append(row)
            names = [p[-1] for p in props]
            if name == 'vertex':
                V = np.array([[r[names.index(c)] for c in 'xyz'] for r in rows])
            elif name == 'face':
                F = np.array([r[[p[0] for p in props].index('list')] for r in rows], dtype=np.int64)
        return V, F
    order = '<' if fmt == 'binary_little_endian' else '>'
    at, V, F = end, None, None
    for name, count, props in elements:
        if all(p[0] != 'list' for p in props):
            dt = np.dtype([(p[1], order + PLY_TYPES[p[0]]) for p in props])
            rec = np.frombuffer(data, dtype=dt, count=count, offset=at)
            at += dt.itemsize * count
            if name == 'vertex':
                V = np.stack([rec[c].astype(np.float64) for c in 'xyz'], 1)
            continue
        # faces: scalar properties, then a list of three indices per face (triangles only)
        fields = []
        for p in props:
            if p[0] == 'list':
                fields += [('n', order + PLY_TYPES[p[1]]), ('v', order + PLY_TYPES[p[2]], (3,))]
            else:
                fields.append((p[-1], order + PLY_TYPES[p[0]]))
        dt = np.dtype(fields)
        rec = np.frombuffer(data, dtype=dt, count=count, offset=at)
        if np.any(rec['n'] != 3):
            sys.exit('refine_scan: only triangle faces are read')
        at += dt.itemsize * count
        F = rec['v'].astype(np.int64)
    return V, F


def read_obj(path):
    V, F = [], []
    for line in open(path):
        w = line.split()
        if w and w[0] == 'v':
            V.append([float(x) for x in w[1:4]])
        elif w and w[0] == 'f':
            F.append([int(x.split('/')[0]) - 1 for x in w[1:4]])
    return np.array(V), np.array(F, dtype=np.int64)


def edges_of(F):
    """Unique undirected edges, and each face's three edge ids (edge i is opposite corner i)."""
    E = np.stack([F[:, [1, 2]], F[:, [2, 0]], F[:, [0, 1]]], 1).reshape(-1, 2)
    E.sort(1)
    unique, inverse = np.unique(E, axis=0, return_inverse=True)
    return unique, inverse.reshape(-1, 3)


def refine(V, F, red):
    """Splits every edge of a `red` face at its midpoint and re-triangulates each face by how many of
    its edges were split (0: kept, 1: two triangles, 2: three, 3: four)."""
    E, FE = edges_of(F)
    split = np.zeros(len(E), bool)
    split[FE[red].ravel()] = True
    mid = np.full(len(E), -1, np.int64)
    mid[split] = len(V) + np.arange(split.sum())
    V = np.vstack([V, 0.5 * (V[E[split, 0]] + V[E[split, 1]])])
    out = []
    s = split[FE]
    count = s.sum(1)
    out.append(F[count == 0])
    for rot in range(3):  # rotate each face so its pattern is canonical: corners a, b, c
        a, b, c = F[:, rot], F[:, (rot + 1) % 3], F[:, (rot + 2) % 3]
        ma, mb, mc = mid[FE[:, rot]], mid[FE[:, (rot + 1) % 3]], mid[FE[:, (rot + 2) % 3]]
        sa, sb, sc = s[:, rot], s[:, (rot + 1) % 3], s[:, (rot + 2) % 3]
        one = (count == 1) & sc  # only edge ab (opposite c) split at mc
        out += [np.stack([a, mc, c], 1)[one], np.stack([mc, b, c], 1)[one]]
        two = (count == 2) & ~sb  # edges ab (mc) and bc (ma) split, ca whole
        out += [np.stack([mc, b, ma], 1)[two], np.stack([a, mc, ma], 1)[two], np.stack([a, ma, c], 1)[two]]
    full = count == 3
    a, b, c = F[full, 0], F[full, 1], F[full, 2]
    ma, mb, mc = mid[FE[full, 0]], mid[FE[full, 1]], mid[FE[full, 2]]
    out += [np.stack([a, mc, mb], 1), np.stack([mc, b, ma], 1), np.stack([mb, ma, c], 1), np.stack([ma, mb, mc], 1)]
    return V, np.vstack(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('mesh')
    ap.add_argument('out')
    ap.add_argument('--vertices', type=int, default=1_000_000)
    a = ap.parse_args()
    V, F = read_ply(a.mesh) if a.mesh.lower().endswith('.ply') else read_obj(a.mesh)
    while True:
        added = len(edges_of(F)[0])
        if len(V) + added > a.vertices:
            break
        V, F = refine(V, F, np.ones(len(F), bool))
    if len(V) < a.vertices:
        height = V[F].mean(1)[:, 2]
        order = np.argsort(height, kind='stable')
        lo, hi = 0, len(F)  # the fewest lowest faces whose refinement reaches the count
        E, FE = edges_of(F)
        while lo < hi:
            m = (lo + hi) // 2
            split = np.zeros(len(E), bool)
            split[FE[order[:m]].ravel()] = True
            if len(V) + split.sum() >= a.vertices:
                hi = m
            else:
                lo = m + 1
        red = np.zeros(len(F), bool)
        red[order[:lo]] = True
        V, F = refine(V, F, red)
    with open(a.out, 'w') as f:
        f.write('\n'.join('v %.9g %.9g %.9g' % tuple(p) for p in V))
        f.write('\n')
        f.write('\n'.join('f %d %d %d' % tuple(t) for t in F + 1))
        f.write('\n')
    print(f'refine_scan: {len(V)} vertices, {len(F)} faces -> {a.out}')


if __name__ == '__main__':
    main()
