#!/usr/bin/env python3
"""Writes the bad-input corpus (tests/data/bad/) and the accepted-with-warning corpus
(tests/data/accepted/) with their EXPECTED.txt tables. The files are committed; this script
documents how each was made and can regenerate them byte for byte: python3 tests/meshio/make_corpus.py

bad/EXPECTED.txt:      <file> TAB <substring>
    `offsetopt check FILE` must exit 2 with the substring on stderr, and load_mesh with strict
    options (flip_inside_out = false, single_component = true) must throw MeshInputError whose
    message contains it.
accepted/EXPECTED.txt: <file> TAB <check exit code> TAB <load warning substring, or - for none>
    load_mesh with default options must succeed (with that warning, or with no warning at all);
    `offsetopt check FILE` must exit with the given code.
"""
import math
import os
import struct

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")
BAD = os.path.join(DATA, "bad")
ACCEPTED = os.path.join(DATA, "accepted")

# Unit cube, faces counter-clockwise seen from outside, as quads (1-based).
CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_Q = [(1, 4, 3, 2), (5, 6, 7, 8), (1, 2, 6, 5), (3, 4, 8, 7), (1, 5, 8, 4), (2, 3, 7, 6)]
CUBE_T = [t for (a, b, c, d) in CUBE_Q for t in ((a, b, c), (a, c, d))]
# Tetrahedron, outward.
TET_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TET_T = [(1, 3, 2), (1, 2, 4), (1, 4, 3), (2, 3, 4)]


def num(x):
    return repr(float(x)) if isinstance(x, float) else str(x)


def obj(vertices, faces, header="", newline="\n"):
    lines = [header] if header else []
    lines += ["v " + " ".join(num(c) for c in v) for v in vertices]
    lines += ["f " + " ".join(str(i) for i in f) for f in faces]
    return (newline.join(lines) + newline).encode()


def off(vertices, faces, keyword="OFF"):
    lines = [keyword, "%d %d 0" % (len(vertices), len(faces))]
    lines += [" ".join(num(c) for c in v) for v in vertices]
    lines += [" ".join([str(len(f))] + [str(i - 1) for i in f]) for f in faces]
    return ("\n".join(lines) + "\n").encode()


def ply_ascii(vertices, faces, count_type="uchar", index_type="int", index_name="vertex_indices"):
    head = ["ply", "format ascii 1.0", "element vertex %d" % len(vertices),
            "property float x", "property float y", "property float z",
            "element face %d" % len(faces),
            "property list %s %s %s" % (count_type, index_type, index_name), "end_header"]
    body = [" ".join(num(c) for c in v) for v in vertices]
    body += [" ".join([str(len(f))] + [str(i - 1) for i in f]) for f in faces]
    return ("\n".join(head + body) + "\n").encode()


SIZES = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I", "float": "f", "double": "d"}


def ply_binary(vertices, faces, endian="<", count_type="uchar", index_type="int", newline="\n",
               coord_type="float", vertex_count=None, face_count=None):
    fmt = "binary_little_endian" if endian == "<" else "binary_big_endian"
    head = ["ply", "format %s 1.0" % fmt, "comment corpus file",
            "element vertex %d" % (len(vertices) if vertex_count is None else vertex_count),
            "property %s x" % coord_type, "property %s y" % coord_type, "property %s z" % coord_type,
            "element face %d" % (len(faces) if face_count is None else face_count),
            "property list %s %s vertex_indices" % (count_type, index_type), "end_header"]
    data = (newline.join(head) + newline).encode()
    for v in vertices:
        data += struct.pack(endian + SIZES[coord_type] * 3, *v)
    for f in faces:
        data += struct.pack(endian + SIZES[count_type], len(f))
        data += struct.pack(endian + SIZES[index_type] * len(f), *[i - 1 for i in f])
    return data


def stl_binary(vertices, faces, header=b"corpus binary STL", count=None):
    data = header.ljust(80, b" ")[:80]
    data += struct.pack("<I", len(faces) if count is None else count)
    for f in faces:
        data += struct.pack("<3f", 0, 0, 0)
        for i in f:
            data += struct.pack("<3f", *vertices[i - 1])
        data += b"\0\0"
    return data


def stl_ascii(vertices, faces, name="cube", upper=False):
    kw = (lambda s: s.upper()) if upper else (lambda s: s)
    out = ["%s %s" % (kw("solid"), name)]
    for f in faces:
        out.append("  %s %s 0 0 0" % (kw("facet"), kw("normal")))
        out.append("    %s %s" % (kw("outer"), kw("loop")))
        for i in f:
            out.append("      %s %s" % (kw("vertex"), " ".join(num(c) for c in vertices[i - 1])))
        out.append("    " + kw("endloop"))
        out.append("  " + kw("endfacet"))
    out.append("%s %s" % (kw("endsolid"), name))
    return ("\n".join(out) + "\n").encode()


def flipped(faces):
    return [(f[0], f[2], f[1]) for f in faces]


def shifted(vertices, faces, dx, offset):
    return [(x + dx, y, z) for (x, y, z) in vertices], [tuple(i + offset for i in f) for f in faces]


def pseudo_random_bytes(n, seed):
    out = bytearray()
    state = seed
    for _ in range(n):
        state = (state * 6364136223846793005 + 1442695040888963407) % (1 << 64)
        out.append(state >> 56)
    return bytes(out)


bad = {}       # name -> (bytes, substring)
accepted = {}  # name -> (bytes, check exit code, warning substring or "-")

# --- file-level problems
bad["empty.obj"] = (b"", "file is empty")
bad["no_faces.obj"] = (obj(CUBE_V, []), "no faces")
bad["garbage.obj"] = (b"v 0 0 0\n" + pseudo_random_bytes(400, 1) + b"\0\n", "binary data")
g = bytearray(pseudo_random_bytes(300, 2)); g[80:84] = struct.pack("<I", 0x7FFFFFFF)
bad["garbage.stl"] = (bytes(g), "claims")
bad["truncated.stl"] = (stl_binary(CUBE_V, CUBE_T)[:84 + 50 * 7], "truncated")
bad["count_wraps_32bit.stl"] = (stl_binary(CUBE_V, CUBE_T[:1], count=2**31 + 1), "claims")
bad["stl_ascii_broken.stl"] = (stl_ascii(CUBE_V, CUBE_T).replace(b"      vertex 0 1 0\n", b"      vertx 0 1 0\n", 1),
                               "expected 'vertex'")
bad["stl_binary_nan.stl"] = (stl_binary([(float("nan"), 0, 0)] + TET_V[1:], TET_T), "not a finite number")
bad["off_counts_beyond_file.off"] = (b"OFF\n1000000 2000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "can hold")
bad["off_binary.off"] = (b"OFF BINARY\n" + struct.pack(">3i", 4, 4, 0), "binary OFF")
bad["ply_counts_beyond_file.ply"] = (ply_ascii(TET_V, TET_T).replace(b"element vertex 4", b"element vertex 1000000"), "can hold")
bad["ply_count_above_cap.ply"] = (ply_ascii(TET_V, TET_T).replace(b"element face 4", b"element face 5000000000"),
                                  "supported maximum")
bad["ply_binary_counts_beyond_file.ply"] = (ply_binary(TET_V, TET_T, face_count=30000000), "can hold")
bad["ply_truncated_binary.ply"] = (ply_binary(CUBE_V, CUBE_T)[:-7], "truncated")
bad["ply_unknown_format.ply"] = (ply_ascii(TET_V, TET_T).replace(b"format ascii", b"format binary_middle_endian"),
                                 "unknown PLY format")
bad["ply_no_end_header.ply"] = (b"ply\nformat ascii 1.0\nelement vertex 0\n", "end_header")
bad["ply_float_list_count.ply"] = (ply_ascii(TET_V, TET_T, count_type="float"), "not an integer type")
# Hostile-input review (issue 7): elements without properties hold no bytes, so their counts (up to the cap)
# pass the size check; the readers used to loop over every instance (minutes per header).
for encoding in ("ascii", "binary_little_endian"):
    bad["ply_empty_elements_%s.ply" % encoding.split("_")[0]] = (
        b"ply\nformat %s 1.0\n" % encoding.encode() + b"element e 33554432\n" * 200 + b"end_header\n", "no faces")
# Found by fuzz_read_ply: the "claims more than the file can hold" message listed every element,
# a line as long as the header (now at most 8 named, then a count).
bad["ply_many_elements_message.ply"] = (
    b"ply\nformat binary_little_endian 1.0\n" + b"element e 33554432\nproperty uchar a\n" * 200 + b"end_header\n",
    "and 192 more elements")
# --- numbers
nan_cube = [("nan", 0, 0)] + CUBE_V[1:]
bad["nan_coordinate.obj"] = (obj(nan_cube, CUBE_T), "not a finite number")
bad["inf_coordinate.off"] = (off([(0, "-inf", 0)] + CUBE_V[1:], CUBE_T), "not a finite number")
bad["huge_coordinate.ply"] = (ply_ascii([(1e300, 0, 0)] + TET_V[1:], TET_T), "exceeds the supported magnitude")
# Hostile-input review (issue 7): tinyobjloader's parser overflowed an int on this exponent
# (undefined behaviour, reported by UBSan) before the OBJ reader gave it placeholder vertices.
bad["exponent_overflows_int.obj"] = (obj([("1e2147483648", 0, 0)] + CUBE_V[1:], CUBE_T), "not a finite number")
bad["not_a_number.obj"] = (obj([("abc", 0, 0)] + CUBE_V[1:], CUBE_T), "is not a number")
bad["missing_coordinate.obj"] = (obj([(1, 0)] + CUBE_V[1:], CUBE_T), "needs 3 coordinates")
bad["non_utf8_coordinate.obj"] = (obj(CUBE_V, CUBE_T).replace(b"v 1 0 0\n", b"v 1 \xff\xfe 0\n", 1), "is not a number")
# --- indices
bad["negative_index.obj"] = (obj(CUBE_V, [(-20, 2, 3)] + CUBE_T[1:]), "out of range")
bad["positive_index_out_of_range.obj"] = (obj(CUBE_V, [(1, 2, 30)] + CUBE_T[1:]), "out of range")
bad["index_20_digits.obj"] = (obj(CUBE_V, [("12345678901234567890", 2, 3)] + CUBE_T[1:]), "does not fit in 32 bits")
bad["index_zero.obj"] = (obj(CUBE_V, [(0, 2, 3)] + CUBE_T[1:]), "index 0")
bad["index_out_of_range.off"] = (off(CUBE_V, [(1, 2, 100)] + CUBE_T[1:]), "out of range")
bad["ply_index_out_of_range.ply"] = (ply_binary(TET_V, [(1, 3, 2000)] + TET_T[1:]), "out of range")
bad["ply_uint_index_overflow.ply"] = (ply_binary(TET_V, [(1, 3, 4000000001)] + TET_T[1:], index_type="uint"),
                                      "does not fit in 32 bits")
bad["face_two_corners.obj"] = (obj(CUBE_V, CUBE_T + [(1, 2)]), "at least 3")
# --- topology and geometry (one defect each)
# A sliver (b, m, a) with m the midpoint of edge a-b closes a split cube face exactly.
sv = CUBE_V + [(0.5, 0, 0)]  # vertex 9 = midpoint of 1-2 (front/bottom edge)
st = [t for t in CUBE_T if t not in [(1, 2, 6)]] + [(1, 9, 6), (9, 2, 6), (2, 9, 1)]
# The bottom face uses edge 2->1 via (1,4,3),(1,3,2): it keeps the direct edge; the sliver pairs it.
# A valid closed solid (OpenSCAD writes T-junctions this way): accepted with a warning (below).
sliver_cube = obj(sv, st)
bad["duplicate_face_opposite.obj"] = (obj(TET_V, TET_T + [(1, 2, 3)]), "repeats the vertices")
bad["boundary_edges.obj"] = (obj(CUBE_V, CUBE_T[:-1]), "not closed")
v2, t2 = [(x, -y, -z) for (x, y, z) in TET_V], [tuple(i + 4 for i in f) for f in TET_T]
edge_shared = TET_V + v2[2:]  # second tetrahedron reuses vertices 1, 2 (the x axis edge)
remap = {5: 1, 6: 2, 7: 5, 8: 6}
bad["non_manifold_edge.obj"] = (obj(edge_shared, TET_T + [tuple(remap[i] for i in f) for f in t2]), "is shared by")
point_shared = TET_V + [(-x, -y, -z) for (x, y, z) in TET_V[1:]]
remap = {5: 1, 6: 5, 7: 6, 8: 7}
bad["non_manifold_vertex.obj"] = (obj(point_shared, TET_T + [tuple(remap[i] for i in f) for f in flipped(t2)]),
                                  "separate fans")
bad["inconsistent_orientation.obj"] = (obj(CUBE_V, CUBE_T[:-1] + flipped(CUBE_T[-1:])), "same direction")
bad["inside_out.obj"] = (obj(CUBE_V, flipped(CUBE_T)), "inside-out")
sv2, st2 = shifted(TET_V, TET_T, 3, 4)
bad["two_components.obj"] = (obj(TET_V + sv2, TET_T + st2), "separate components")
pillow_v = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
pillow_t = [(1, 2, 3), (1, 3, 4), (1, 4, 2), (2, 4, 3)]
bad["zero_volume.obj"] = (obj(pillow_v, pillow_t), "zero volume")
inner_v = [(0.25 + 0.5 * x, 0.25 + 0.5 * y, 0.25 + 0.5 * z) for (x, y, z) in CUBE_V]
inner_t = [tuple(i + 8 for i in f) for f in CUBE_T]  # same orientation as the outer: wrong for a cavity
bad["cavity_facing_out.obj"] = (obj(CUBE_V + inner_v, CUBE_T + inner_t), "cavity shell has positive")
# A cavity that pokes out of its part and holds more than it: each shell faces the right way for
# the nesting found at its one test point, but the volumes sum to 48 - 72.5 < 0 (found by fuzzing).
slab_v = [(4 * x, 4 * y, 3 * z) for (x, y, z) in CUBE_V]
poking_v = [(0.5 + 5 * x, 0.5 + 5 * y, 1 + 2.9 * z) for (x, y, z) in CUBE_V]
poking_t = flipped([tuple(i + 8 for i in f) for f in CUBE_T])
bad["cavity_larger_than_part.obj"] = (obj(slab_v + poking_v, CUBE_T + poking_t), "signed volumes sum to -24.5")

# --- accepted, some with warnings
accepted["crlf.obj"] = (obj(CUBE_V, CUBE_T, newline="\r\n"), 0, "-")
accepted["lone_cr.obj"] = (obj(CUBE_V, CUBE_T, newline="\r"), 0, "-")
accepted["crlf_header_binary.ply"] = (ply_binary(CUBE_V, CUBE_T, newline="\r\n"), 0, "-")
accepted["solid_header_binary.stl"] = (stl_binary(CUBE_V, CUBE_T, header=b"solid cube exported by a CAD tool"), 0, "-")
accepted["big_endian.ply"] = (ply_binary(CUBE_V, CUBE_T, endian=">"), 0, "-")
accepted["big_endian_double.ply"] = (ply_binary(CUBE_V, CUBE_T, endian=">", coord_type="double", index_type="uint"), 0, "-")
accepted["ushort_list_count.ply"] = (ply_binary(CUBE_V, CUBE_T, count_type="ushort", index_type="uint"), 0, "-")
accepted["uint_list_count.ply"] = (ply_ascii(CUBE_V, CUBE_T, count_type="uint", index_type="int"), 0, "-")
accepted["vertex_index_name.ply"] = (ply_ascii(CUBE_V, CUBE_T, index_name="vertex_index"), 0, "-")
extra = ("ply\nformat ascii 1.0\ncomment extra properties and elements are skipped\nobj_info test\n"
         "element vertex 8\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
         "property uchar red\nproperty list uchar float texcoord\n"
         "element face 12\nproperty uchar intensity\nproperty list uchar int vertex_indices\nproperty int flags\n"
         "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n")
extra += "".join("%s 0.5 255 2 0.25 0.75\n" % " ".join(num(c) for c in v) for v in CUBE_V)
extra += "".join("7 3 %s -1\n" % " ".join(str(i - 1) for i in f) for f in CUBE_T)
extra += "0 1\n"
accepted["extra_properties.ply"] = (extra.encode(), 0, "-")
accepted["quads.obj"] = (obj(CUBE_V, CUBE_Q), 0, "fan-triangulated")
accepted["quads.off"] = (off(CUBE_V, CUBE_Q), 0, "fan-triangulated")
accepted["mtllib_dev_zero.obj"] = (obj(CUBE_V, CUBE_T, header=(
    "mtllib ../../../../../../../../dev/zero\nusemtl zero\no cube\ng side\ns 1\nvt 0 0\nvn 0 0 1\n"
    "t crease 8192/8192/8192\nvw 1 0 0.5\nl 1 2\np 3")), 0, "material library")
accepted["non_utf8_comment.obj"] = (obj(CUBE_V, CUBE_T, header="# caf\u00e9 Zo\u00eb").replace(
    b"\xc3\xa9", b"\xe9") + b"g \xff\xfe\x80\n", 0, "-")
accepted["negative_relative_index.obj"] = (obj(CUBE_V, [tuple(i - 9 for i in f) for f in CUBE_T]), 0, "-")
accepted["vertex_colours.obj"] = (b"".join(b"v %s 0.5 0.25 1\n" % " ".join(num(c) for c in v).encode() for v in CUBE_V) +
                                  b"".join(b"f %d/%d %d/%d %d/%d\n" % (a, a, b, b, c, c) for (a, b, c) in CUBE_T), 0, "-")
accepted["comments_colours.off"] = (b"# a comment\nCOFF\n# another\n8 12 18\n" +
                                    b"".join(b"%s 255 0 0 255 # red\n" % " ".join(num(c) for c in v).encode() for v in CUBE_V) +
                                    b"".join(b"3 %d %d %d 0.5 0.5 0.5\n" % tuple(i - 1 for i in f) for f in CUBE_T), 0, "-")
accepted["no_final_newline.off"] = (off(CUBE_V, CUBE_T).rstrip(b"\n"), 0, "-")
accepted["uppercase_keywords.stl"] = (stl_ascii(CUBE_V, CUBE_T, upper=True), 0, "-")
accepted["two_solid_blocks.stl"] = (stl_ascii(CUBE_V, CUBE_T[:6], "a") + stl_ascii(CUBE_V, CUBE_T[6:], "b"), 0, "-")
accepted["trailing_bytes.stl"] = (stl_binary(CUBE_V, CUBE_T) + b"\0" * 17, 0, "bytes after the last")
accepted["unreferenced_vertex.obj"] = (obj(CUBE_V + [(5, 5, 5)], CUBE_T), 0, "unreferenced")
accepted["unreferenced_nan_vertex.obj"] = (obj(CUBE_V + [("nan", "nan", "nan")], CUBE_T), 2, "unreferenced")
accepted["inside_out.obj"] = bad["inside_out.obj"][:1] + (2, "every face flipped")
accepted["inside_out_binary.stl"] = (stl_binary(CUBE_V, flipped(CUBE_T)), 2, "every face flipped")
accepted["two_components.obj"] = bad["two_components.obj"][:1] + (2, "separate closed shells")
accepted["hollow_cube.obj"] = (obj(CUBE_V + inner_v, CUBE_T + flipped(inner_t)), 2, "separate closed shells")
accepted["duplicate_face_same.obj"] = (obj(TET_V, TET_T + [TET_T[2]]), 2, "duplicate face")
accepted["sliver_face.obj"] = (sliver_cube, 0, "zero-area face")
# OBJ corner dialects with empty texture or normal parts (issue 13).
accepted["corners_trailing_slash.obj"] = (obj(CUBE_V, [tuple("%d/1/" % i for i in f) for f in CUBE_T],
                                              header="vt 0 0"), 0, "-")
accepted["corners_double_slash.obj"] = (obj(CUBE_V, [tuple("%d//" % i for i in f) for f in CUBE_T]), 0, "-")
# A prism whose caps are 300-corner polygons (tinyobjloader rc10 keeps corner counts in a byte).
prism_n = 300
prism_ring = [(round(10 * math.cos(2 * math.pi * i / prism_n), 6), round(10 * math.sin(2 * math.pi * i / prism_n), 6))
              for i in range(prism_n)]
prism_v = [(x, y, 0.0) for (x, y) in prism_ring] + [(x, y, 5.0) for (x, y) in prism_ring]
prism_f = [tuple(range(prism_n, 0, -1)), tuple(range(prism_n + 1, 2 * prism_n + 1))]
prism_f += [(i + 1, (i + 1) % prism_n + 1, (i + 1) % prism_n + 1 + prism_n, i + 1 + prism_n) for i in range(prism_n)]
accepted["prism_300_corners.obj"] = (obj(prism_v, prism_f), 0, "fan-triangulated")
# An L-shaped prism: non-convex caps, ear-clipped in their plane.
ell = [(1, 1), (1, 3), (0, 3), (0, 0), (3, 0), (3, 1)]
ell_v = [(x, y, 0) for (x, y) in ell] + [(x, y, 2) for (x, y) in ell]
ell_f = [(6, 5, 4, 3, 2, 1), (7, 8, 9, 10, 11, 12)] + [(i + 1, (i + 1) % 6 + 1, (i + 1) % 6 + 7, i + 7) for i in range(6)]
accepted["l_prism.obj"] = (obj(ell_v, ell_f), 0, "ear clipping")
# Two cubes touching at one corner, written with two vertex indices there: a pinch (check: exit 2).
pinch_v = CUBE_V + [(x + 1, y + 1, z + 1) for (x, y, z) in CUBE_V]
accepted["pinched_cubes.obj"] = (obj(pinch_v, CUBE_T + [tuple(i + 8 for i in f) for f in CUBE_T]), 2, "separate closed shells")
collapsed = stl_ascii(CUBE_V, CUBE_T).replace(b"endsolid cube",
    b"facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid cube")
accepted["collapsed_facet.stl"] = (collapsed, 2, "with a repeated vertex")


# 3MF packages (3MF Core 1.3): zips of [Content_Types].xml, _rels/.rels and model parts, written
# with a fixed timestamp so the bytes are reproducible (deflate output depends on zlib's version).
import zlib
import zipfile
import io

CT = (b'<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
      b'<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
      b'<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>\n')
RELS = (b'<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
        b'<Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>'
        b'</Relationships>\n')
NS = 'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"'
PNS = 'xmlns:p="http://schemas.microsoft.com/3dmanufacturing/production/2015/06"'


def mesh_xml(vertices, faces):
    """<mesh> of 0-based triangles from 1-based corpus faces."""
    return ("<mesh><vertices>" + "".join('<vertex x="%s" y="%s" z="%s"/>' % tuple(num(c) for c in v) for v in vertices) +
            "</vertices><triangles>" + "".join('<triangle v1="%d" v2="%d" v3="%d"/>' % tuple(i - 1 for i in f) for f in faces) +
            "</triangles></mesh>")


def model_xml(objects, items, unit="millimeter", extra_ns=""):
    return ('<?xml version="1.0" encoding="UTF-8"?>\n<model unit="%s" xml:lang="en-US" %s %s><resources>%s</resources>'
            '<build>%s</build></model>\n' % (unit, NS, extra_ns, "".join(objects), "".join(items))).encode()


def package(parts, method=zipfile.ZIP_DEFLATED):
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as z:
        for name, data in parts:
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = method
            info.create_system = 0
            z.writestr(info, data)
    return buffer.getvalue()


def cube_3mf(**kw):
    obj_xml = '<object id="1" type="model">' + mesh_xml(CUBE_V, CUBE_T) + '</object>'
    return package([("[Content_Types].xml", CT), ("_rels/.rels", RELS),
                    ("3D/3dmodel.model", model_xml([obj_xml], ['<item objectid="1"/>'], **kw))])


good3 = cube_3mf()
accepted["cube_deflate.3mf"] = (good3, 0, "-")
accepted["cube_inch.3mf"] = (cube_3mf(unit="inch"), 0, "unit is inch")
# Bambu Studio / OrcaSlicer style: the build names an assembly whose component lives in another part.
child = model_xml(['<object id="1" type="model">' + mesh_xml(CUBE_V, CUBE_T) + '</object>'], [])
root = model_xml(['<object id="2" type="model"><components><component p:path="/3D/Objects/object_1.model" objectid="1" '
                  'transform="1 0 0 0 1 0 0 0 1 10 20 30"/></components></object>'],
                 ['<item objectid="2" transform="1 0 0 0 1 0 0 0 1 0 0 5"/>'], extra_ns=PNS)
accepted["components_in_other_part.3mf"] = (package([("[Content_Types].xml", CT), ("_rels/.rels", RELS),
                                                     ("3D/3dmodel.model", root), ("3D/Objects/object_1.model", child)]), 0, "-")
# A mirroring item transform: the reader reverses the triangles so the solid still faces out.
mirror = model_xml(['<object id="1" type="model">' + mesh_xml(CUBE_V, CUBE_T) + '</object>'],
                   ['<item objectid="1" transform="-1 0 0 0 1 0 0 0 1 0 0 0"/>'])
accepted["mirrored_item.3mf"] = (package([("[Content_Types].xml", CT), ("_rels/.rels", RELS), ("3D/3dmodel.model", mirror)]), 0, "-")


def corrupt_crc(data):
    """Flips one byte of the model entry's data (stored), leaving the CRC as it was."""
    at = data.index(b"<vertices>") + 3
    return data[:at] + bytes([data[at] ^ 0x20]) + data[at + 1:]


stored = package([("[Content_Types].xml", CT), ("_rels/.rels", RELS),
                  ("3D/3dmodel.model", model_xml(['<object id="1">' + mesh_xml(CUBE_V, CUBE_T) + '</object>'],
                                                 ['<item objectid="1"/>']))], method=zipfile.ZIP_STORED)
bad["3mf_crc_mismatch.3mf"] = (corrupt_crc(stored), "CRC-32 mismatch")
bad["3mf_truncated.3mf"] = (good3[:len(good3) // 2], "no end of central directory")


def deflate_entry_patched(data, name, new_compressed, declared_size):
    """Rebuilds a one-entry-changed package by hand: replaces `name`'s deflate data."""
    z = zipfile.ZipFile(io.BytesIO(data))
    parts = [(i.filename, z.read(i.filename)) for i in z.infolist()]
    out, central = b"", b""
    for fname, content in parts:
        comp = zlib.compressobj(9, zlib.DEFLATED, -15)
        body = comp.compress(content) + comp.flush()
        size, crc = len(content), zlib.crc32(content)
        if fname == name:
            body, size = new_compressed, declared_size
        offset = len(out)
        fn = fname.encode()
        out += struct.pack("<IHHHHHIIIHH", 0x04034b50, 20, 0, 8, 0, 33, crc, len(body), size, len(fn), 0) + fn + body
        central += struct.pack("<IHHHHHHIIIHHHHHII", 0x02014b50, 20, 20, 0, 8, 0, 33, crc, len(body), size, len(fn), 0, 0,
                               0, 0, 0, offset) + fn
    return out + central + struct.pack("<IHHHHIIH", 0x06054b50, 0, 0, len(parts), len(parts), len(central), len(out), 0)


bomb = zlib.compressobj(9, zlib.DEFLATED, -15)
bomb_data = bomb.compress(b"<" * (10 << 20)) + bomb.flush()
bad["3mf_deflate_bomb.3mf"] = (deflate_entry_patched(good3, "3D/3dmodel.model", bomb_data, 1000), "inflates to more than the declared")
bad["3mf_corrupt_deflate.3mf"] = (deflate_entry_patched(good3, "3D/3dmodel.model", b"\xff" * 40, 1000), "corrupt deflate data")


def cube_with_model(model):
    return package([("[Content_Types].xml", CT), ("_rels/.rels", RELS), ("3D/3dmodel.model", model)])


bad["3mf_index_out_of_range.3mf"] = (cube_with_model(model_xml(
    ['<object id="1">' + mesh_xml(CUBE_V, CUBE_T[:-1] + [(1, 2, 9)]) + '</object>'], ['<item objectid="1"/>'])), "uses vertex 8")
bad["3mf_doctype.3mf"] = (cube_with_model(b'<?xml version="1.0"?>\n<!DOCTYPE model [<!ENTITY a "aaaa">]>\n' +
                                          model_xml(['<object id="1">' + mesh_xml(CUBE_V, CUBE_T) + '</object>'],
                                                    ['<item objectid="1"/>']).split(b"\n", 1)[1]), "DOCTYPE")
bad["3mf_component_cycle.3mf"] = (cube_with_model(model_xml(
    ['<object id="1"><components><component objectid="2"/></components></object>',
     '<object id="2"><components><component objectid="1"/></components></object>'], ['<item objectid="1"/>'])),
    "nested deeper than 32")
bad["3mf_no_model_part.3mf"] = (package([("[Content_Types].xml", CT), ("3D/other.model", b"<model/>")]), "no 3D model part")
bad["3mf_unknown_unit.3mf"] = (cube_3mf(unit="parsec"), "unknown unit")
bad["3mf_bad_number.3mf"] = (cube_with_model(model_xml(
    ['<object id="1">' + mesh_xml([("1,5", 0, 0)] + CUBE_V[1:], CUBE_T) + '</object>'], ['<item objectid="1"/>'])), "is not a number")
bad["3mf_mismatched_tag.3mf"] = (cube_with_model(model_xml(
    ['<object id="1">' + mesh_xml(CUBE_V, CUBE_T).replace("</triangles>", "</vertices>") + '</object>'],
    ['<item objectid="1"/>'])), "does not match")
bad["3mf_no_build_item.3mf"] = (cube_with_model(model_xml(['<object id="1">' + mesh_xml(CUBE_V, CUBE_T) + '</object>'], [])),
                                "no <item> in <build>")


def write(folder, table, rows):
    os.makedirs(folder, exist_ok=True)
    for name, row in sorted(table.items()):
        with open(os.path.join(folder, name), "wb") as f:
            f.write(row[0])
    with open(os.path.join(folder, "EXPECTED.txt"), "w") as f:
        f.write(rows)
        for name, row in sorted(table.items()):
            f.write("\t".join([name] + [str(x) for x in row[1:]]) + "\n")


write(BAD, bad, "# file\tsubstring expected from `offsetopt check` (exit 2) and from strict load_mesh\n")
write(ACCEPTED, accepted, "# file\tcheck exit code\tload_mesh warning substring (- for no warning)\n")
print("bad: %d files, accepted: %d files" % (len(bad), len(accepted)))
