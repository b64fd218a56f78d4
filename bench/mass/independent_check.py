#!/usr/bin/python3
"""Independent check of `offsetopt inspect` on real meshes.

Reads each mesh with its own minimal numpy readers (OFF, OBJ, PLY ascii/binary, STL), computes
volume, centre of mass and the inertia tensor about it by signed-tetrahedron decomposition with
math.fsum (exactly rounded sums, unlike the tool's Neumaier sums in C++), and prints the largest
relative difference against the tool's JSON report. Skips cleanly when ../shared/meshes is absent.

usage: /usr/bin/python3 bench/mass/independent_check.py [BINARY] [MESH...]
"""
import json
import math
import os
import struct
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def read_off(path):
    tokens = []
    with open(path) as f:
        for line in f:
            line = line.split('#', 1)[0].split()
            tokens.extend(line)
    assert tokens[0].endswith('OFF')
    nv, nf = int(tokens[1]), int(tokens[2])
    pos = 4
    V = np.array(tokens[pos:pos + 3 * nv], dtype=float).reshape(nv, 3)
    pos += 3 * nv
    faces = []
    for _ in range(nf):
        k = int(tokens[pos])
        idx = [int(t) for t in tokens[pos + 1:pos + 1 + k]]
        pos += 1 + k
        faces.extend([idx[0], idx[i], idx[i + 1]] for i in range(1, k - 1))
    return V, np.array(faces, dtype=np.int64)


def read_obj(path):
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == 'v':
                verts.append([float(x) for x in p[1:4]])
            elif p[0] == 'f':
                idx = [int(c.split('/')[0]) for c in p[1:]]
                idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                faces.extend([idx[0], idx[i], idx[i + 1]] for i in range(1, len(idx) - 1))
    return np.array(verts), np.array(faces, dtype=np.int64)


PLY_TYPES = {'char': 'i1', 'int8': 'i1', 'uchar': 'u1', 'uint8': 'u1', 'short': 'i2', 'int16': 'i2',
             'ushort': 'u2', 'uint16': 'u2', 'int': 'i4', 'int32': 'i4', 'uint': 'u4', 'uint32': 'u4',
             'float': 'f4', 'float32': 'f4', 'double': 'f8', 'float64': 'f8'}


def read_ply(path):
    data = open(path, 'rb').read()
    end = data.index(b'end_header') + len(b'end_header')
    while data[end:end + 1] in (b'\r', b'\n'):
        end += 1
        if data[end - 1:end] == b'\n':
            break
    header = data[:end].decode('ascii').replace('\r', '').split('\n')
    fmt, elements = None, []
    for line in header:
        p = line.split()
        if not p:
            continue
        if p[0] == 'format':
            fmt = p[1]
        elif p[0] == 'element':
            elements.append([p[1], int(p[2]), []])
        elif p[0] == 'property':
            elements[-1][2].append(p[1:])
    body = data[end:]
    V, F = None, []
    if fmt == 'ascii':
        tokens = body.split()
        pos = 0
        for name, count, props in elements:
            rows = []
            for _ in range(count):
                row = []
                for prop in props:
                    if prop[0] == 'list':
                        k = int(tokens[pos]); pos += 1
                        row.append([int(t) for t in tokens[pos:pos + k]]); pos += k
                    else:
                        row.append(float(tokens[pos])); pos += 1
                rows.append(row)
            if name == 'vertex':
                names = [p[-1] for p in props]
                V = np.array([[r[names.index(c)] for c in 'xyz'] for r in rows])
            elif name == 'face':
                for r in rows:
                    idx = r[0]
                    F.extend([idx[0], idx[i], idx[i + 1]] for i in range(1, len(idx) - 1))
        return V, np.array(F, dtype=np.int64)
    order = '<' if fmt == 'binary_little_endian' else '>'
    pos = 0
    for name, count, props in elements:
        if all(p[0] != 'list' for p in props):
            dtype = np.dtype([(p[-1], order + PLY_TYPES[p[0]]) for p in props])
            arr = np.frombuffer(body, dtype=dtype, count=count, offset=pos)
            pos += dtype.itemsize * count
            if name == 'vertex':
                V = np.stack([arr[c].astype(float) for c in 'xyz'], axis=1)
            continue
        for _ in range(count):
            for p in props:
                if p[0] == 'list':
                    ct = np.dtype(order + PLY_TYPES[p[1]]); it = np.dtype(order + PLY_TYPES[p[2]])
                    k = int(np.frombuffer(body, ct, 1, pos)[0]); pos += ct.itemsize
                    idx = np.frombuffer(body, it, k, pos).astype(np.int64); pos += it.itemsize * k
                    if name == 'face':
                        F.extend([idx[0], idx[i], idx[i + 1]] for i in range(1, k - 1))
                else:
                    pos += np.dtype(PLY_TYPES[p[0]]).itemsize
    return V, np.array(F, dtype=np.int64)


def read_stl(path):
    data = open(path, 'rb').read()
    if len(data) >= 84 and 84 + 50 * struct.unpack('<I', data[80:84])[0] == len(data):
        n = struct.unpack('<I', data[80:84])[0]
        rec = np.frombuffer(data, dtype=np.dtype([('n', '<f4', 3), ('v', '<f4', (3, 3)), ('a', '<u2')]), count=n, offset=84)
        corners = rec['v'].reshape(-1, 3).astype(float)
    else:
        corners = np.array([[float(x) for x in l.split()[1:4]] for l in data.decode().splitlines() if l.strip().startswith('vertex')])
    V, inverse = np.unique(corners, axis=0, return_inverse=True)
    return V, inverse.reshape(-1, 3).astype(np.int64)


def read_mesh(path):
    ext = os.path.splitext(path)[1].lower()
    return {'.off': read_off, '.obj': read_obj, '.ply': read_ply, '.stl': read_stl}[ext](path)


def properties(V, F):
    used = np.unique(F)
    o = V[used].mean(axis=0)
    a, b, c = V[F[:, 0]] - o, V[F[:, 1]] - o, V[F[:, 2]] - o
    D = np.einsum('ij,ij->i', a, np.cross(b, c))
    if math.fsum(D) < 0:  # inside-out file: the tool flips it, so do the same
        D = -D
        a, b = b, a
    S = a + b + c
    vol = math.fsum(D) / 6.0
    first = [math.fsum(D * S[:, i]) / 24.0 for i in range(3)]
    second = np.zeros((3, 3))
    for i in range(3):
        for j in range(3):
            g = a[:, i] * a[:, j] + b[:, i] * b[:, j] + c[:, i] * c[:, j] + S[:, i] * S[:, j]
            second[i, j] = math.fsum(D * g) / 120.0
    com_local = np.array(first) / vol
    cov = second - vol * np.outer(com_local, com_local)  # ∫ r rᵀ about the centre of mass
    inertia = np.trace(cov) * np.eye(3) - cov
    return vol, com_local + o, inertia


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, 'build', 'offsetopt')
    meshes = sys.argv[2:]
    if not meshes:
        shared = os.path.join(ROOT, '..', 'shared', 'meshes')
        if not os.path.isdir(shared):
            print('skipped: ../shared/meshes is absent')
            return 0
        meshes = sorted(os.path.join(shared, f) for f in os.listdir(shared)
                        if os.path.splitext(f)[1].lower() in ('.off', '.obj', '.ply', '.stl'))
    worst = 0.0
    print(f"{'mesh':24} {'faces':>8} {'volume':>14} {'rel d(volume)':>14} {'rel d(com)':>11} {'rel d(I)':>11}")
    for path in meshes:
        V, F = read_mesh(path)
        vol, com, inertia = properties(V, F)
        report = json.loads(subprocess.run([binary, 'inspect', path, '--json', '-'], check=True,
                                           capture_output=True, text=True).stdout)
        t = report['inertia']
        tool_I = np.array([[t['xx'], t['xy'], t['zx']], [t['xy'], t['yy'], t['yz']], [t['zx'], t['yz'], t['zz']]])
        size = np.linalg.norm(V.max(axis=0) - V.min(axis=0))
        d_vol = abs(report['volume'] - vol) / abs(vol)
        d_com = np.abs(np.array(report['center_of_mass']) - com).max() / size
        d_I = np.abs(tool_I - inertia).max() / np.abs(inertia).max()
        worst = max(worst, d_vol, d_com, d_I)
        print(f"{os.path.basename(path):24} {len(F):8d} {vol:14.8g} {d_vol:14.2e} {d_com:11.2e} {d_I:11.2e}")
    print(f"largest relative difference: {worst:.2e}")
    return 0 if worst < 1e-9 else 1


if __name__ == '__main__':
    sys.exit(main())
