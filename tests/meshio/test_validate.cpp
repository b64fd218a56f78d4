// validate_mesh on constructed meshes: each defect found with the right count and first index
// (edge defects checked against an independent std::map census), valid primitives pass with the
// right genus and volume, and load_mesh's repair-or-refuse policy.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "mesh/primitives.h"
#include "meshio/load_mesh.h"
#include "meshio/validate_mesh.h"
#include "meshio_test_util.h"
#include "util/det_math.h"
#include "util/rng.h"

using namespace offsetopt;
using namespace meshio_test;

namespace {

Mesh unit_box() { return make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3)); }

Mesh tetrahedron() {
  Mesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return m;
}

Mesh flipped(Mesh m) {
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) std::swap(m.F(f, 1), m.F(f, 2));
  return m;
}

// a followed by b, b's vertices shifted by `offset` and renumbered after a's.
Mesh join(const Mesh& a, const Mesh& b, const Eigen::RowVector3d& offset) {
  Mesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V.rowwise() + offset;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, b.F.array() + static_cast<int>(a.V.rows());
  return m;
}

Mesh without_faces(const Mesh& m, std::vector<int> drop) {
  Mesh out;
  out.V = m.V;
  out.F.resize(m.F.rows() - static_cast<Eigen::Index>(drop.size()), 3);
  Eigen::Index row = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    if (std::find(drop.begin(), drop.end(), static_cast<int>(f)) == drop.end()) out.F.row(row++) = m.F.row(f);
  return out;
}

Mesh with_face(Mesh m, int a, int b, int c) {
  m.F.conservativeResize(m.F.rows() + 1, 3);
  m.F.row(m.F.rows() - 1) << a, b, c;
  return m;
}

// Independent signed volume: plain sum of det / 6 about the origin.
double plain_volume(const Mesh& m) {
  double v = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

std::vector<DefectKind> kinds(const MeshValidation& v) {
  std::vector<DefectKind> out;
  for (const Defect& d : v.defects) out.push_back(d.kind);
  return out;
}

}  // namespace

TEST_CASE("valid primitives pass with the right genus, components and volume") {
  const double pi = kPi;
  struct Case {
    const char* name;
    Mesh mesh;
    long long genus;
  };
  const Case cases[] = {{"box", unit_box(), 0},
                        {"icosphere", make_icosphere(1.5, 3), 0},
                        {"torus", make_torus(2.0, 0.5, 32, 16), 1},
                        {"capsule", make_capsule(0.5, 1.0, 16, 4, 3), 0}};
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const MeshValidation v = validate_mesh(c.mesh);
    CHECK(v.valid());
    CHECK(v.components == 1);
    CHECK(v.genus == c.genus);
    CHECK(v.euler_characteristic == 2 - 2 * c.genus);
    CHECK(v.edges == 3 * c.mesh.F.rows() / 2);
    REQUIRE(v.volume_computed);
    CHECK(v.volume == doctest::Approx(plain_volume(c.mesh)).epsilon(1e-12));
  }
  CHECK(validate_mesh(unit_box()).volume == 6.0);
  // The discretised torus's volume is below 2 pi^2 R r^2 and close to it.
  const double torus = validate_mesh(make_torus(2.0, 0.5, 64, 32)).volume;
  CHECK(torus < 2 * pi * pi * 2.0 * 0.25);
  CHECK(torus > 0.99 * 2 * pi * pi * 2.0 * 0.25);
}

TEST_CASE("empty mesh, non-finite and too large coordinates, indices out of range") {
  Mesh empty;
  empty.V = unit_box().V;
  MeshValidation v = validate_mesh(empty);
  REQUIRE(kinds(v) == std::vector<DefectKind>{DefectKind::empty_mesh});
  CHECK(v.defects[0].bound == 8);

  Mesh m = unit_box();
  m.V(3, 1) = std::numeric_limits<double>::quiet_NaN();
  m.V(5, 0) = -std::numeric_limits<double>::infinity();
  m.V(6, 2) = 1e13;
  m.V(7, 0) = -1e12;  // exactly at the limit: fine
  v = validate_mesh(m);
  const Defect* nf = v.find(DefectKind::non_finite_coordinate);
  REQUIRE(nf);
  CHECK(nf->count == 2);
  CHECK(nf->vertex == 3);
  CHECK(std::isnan(nf->value));
  const Defect* large = v.find(DefectKind::coordinate_too_large);
  REQUIRE(large);
  CHECK(large->count == 1);
  CHECK(large->vertex == 6);
  CHECK(large->value == 1e13);
  CHECK(!v.volume_computed);  // no volume from non-finite coordinates
  CHECK(describe_defect(*nf) == "coordinate 'nan' is not a finite number");

  m = unit_box();
  m.F(4, 1) = 8;
  m.F(7, 0) = -1;
  m.F(9, 2) = kIndexOverflow;
  v = validate_mesh(m);
  REQUIRE(kinds(v) == std::vector<DefectKind>{DefectKind::index_out_of_range});
  CHECK(v.defects[0].count == 3);
  CHECK(v.defects[0].face == 4);
  CHECK(v.defects[0].value == 8);
  CHECK(v.defects[0].bound == 8);
}

TEST_CASE("degenerate faces: a repeated vertex is a defect, exactly zero area with distinct corners a note") {
  Mesh m = unit_box();
  m.F(5, 2) = m.F(5, 0);
  MeshValidation v = validate_mesh(m);
  const Defect* d = v.find(DefectKind::degenerate_face);
  REQUIRE(d);
  CHECK(d->count == 1);
  CHECK(d->face == 5);
  CHECK(v.repeated_vertex_faces == 1);
  CHECK(v.droppable_faces == std::vector<long long>{5});

  // A sliver (b, m, a) with m the midpoint of edge a-b closes a split face exactly.
  m = unit_box();
  m.V.conservativeResize(9, 3);
  m.V.row(8) = 0.5 * (m.V.row(0) + m.V.row(1));
  // Face 4 = {0, 1, 4} on y = lo is split at the midpoint 8 of edge 0-1.
  m.F.row(4) << 0, 8, 4;
  m = with_face(m, 8, 1, 4);
  m = with_face(m, 1, 8, 0);  // the zero-area sliver, face 13
  v = validate_mesh(m);
  CHECK(v.valid());  // a closed solid (OpenSCAD closes T-junctions this way)
  CHECK(v.zero_area_faces == 1);
  CHECK(v.first_zero_area_face == 13);
  CHECK(v.droppable_faces.empty());
  CHECK(v.volume == doctest::Approx(6.0));
}

TEST_CASE("duplicate faces in either orientation") {
  Mesh m = with_face(with_face(unit_box(), 2, 6, 3), 5, 7, 3);  // copy of face 6, reversed copy of face 11
  const MeshValidation v = validate_mesh(m);
  const Defect* d = v.find(DefectKind::duplicate_face);
  REQUIRE(d);
  CHECK(d->count == 2);
  CHECK(d->face == 12);
  CHECK(d->other_face == 6);
  CHECK(d->value == 1);
  CHECK(v.same_orientation_duplicates == 1);
  CHECK(v.droppable_faces == std::vector<long long>{12});
  CHECK(v.find(DefectKind::non_manifold_edge));  // each copy puts a third face on three edges
}

TEST_CASE("edge defects agree with an independent census") {
  SUBCASE("boundary") {
    const Mesh m = without_faces(unit_box(), {10, 11});
    const MeshValidation v = validate_mesh(m);
    const EdgeCensus census = edge_census(m);
    const Defect* d = v.find(DefectKind::boundary_edge);
    REQUIRE(d);
    CHECK(census.boundary == 4);
    CHECK(d->count == census.boundary);
    CHECK(d->face == census.first_boundary_face);
    CHECK(v.edges == census.edges);
    CHECK(!v.volume_computed);
    CHECK(v.genus == -1);
  }
  SUBCASE("inconsistent orientation") {
    Mesh m = unit_box();
    std::swap(m.F(7, 1), m.F(7, 2));
    const MeshValidation v = validate_mesh(m);
    const EdgeCensus census = edge_census(m);
    const Defect* d = v.find(DefectKind::inconsistent_orientation);
    REQUIRE(d);
    CHECK(census.inconsistent == 3);
    CHECK(d->count == 3);
    CHECK(d->face == census.first_inconsistent_face);
    CHECK(kinds(v) == std::vector<DefectKind>{DefectKind::inconsistent_orientation});
  }
  SUBCASE("non-manifold edge: two tetrahedra sharing an edge") {
    Mesh m = tetrahedron();
    Mesh rotated = tetrahedron();
    rotated.V.col(1) *= -1;
    rotated.V.col(2) *= -1;  // 180 degrees about x: orientation kept, shares edge 0-1
    Mesh both = join(m, rotated, Eigen::RowVector3d::Zero());
    for (Eigen::Index f = 4; f < 8; ++f)
      for (int k = 0; k < 3; ++k)
        if (both.F(f, k) == 4) both.F(f, k) = 0;
        else if (both.F(f, k) == 5) both.F(f, k) = 1;
    const MeshValidation v = validate_mesh(both);
    const EdgeCensus census = edge_census(both);
    REQUIRE(kinds(v) == std::vector<DefectKind>{DefectKind::non_manifold_edge});
    CHECK(v.defects[0].count == 1);
    CHECK(census.non_manifold == 1);
    CHECK(v.defects[0].face == census.first_non_manifold_face);
    CHECK(v.defects[0].value == 4);
    CHECK(v.defects[0].edge_from == 0);
    CHECK(v.defects[0].edge_to == 1);
  }
  SUBCASE("random holes and flips") {
    Rng rng(20150801);
    for (int trial = 0; trial < 40; ++trial) {
      Mesh m = make_icosphere(1.0, 2);
      for (Eigen::Index f = 0; f < m.F.rows(); ++f)
        if (rng.uniform() < 0.05) std::swap(m.F(f, 1), m.F(f, 2));
      std::vector<int> drop;
      for (int f = 0; f < m.F.rows(); ++f)
        if (rng.uniform() < 0.03) drop.push_back(f);
      m = without_faces(m, drop);
      const MeshValidation v = validate_mesh(m);
      const EdgeCensus census = edge_census(m);
      const Defect* boundary = v.find(DefectKind::boundary_edge);
      const Defect* inconsistent = v.find(DefectKind::inconsistent_orientation);
      CHECK((boundary ? boundary->count : 0) == census.boundary);
      CHECK((boundary ? boundary->face : -1) == census.first_boundary_face);
      CHECK((inconsistent ? inconsistent->count : 0) == census.inconsistent);
      CHECK((inconsistent ? inconsistent->face : -1) == census.first_inconsistent_face);
      CHECK(v.edges == census.edges);
    }
  }
}

TEST_CASE("non-manifold vertex: two tetrahedra touching at one corner") {
  Mesh mirrored = tetrahedron();
  mirrored.V *= -1;  // point reflection reverses orientation
  mirrored = flipped(mirrored);
  Mesh both = join(tetrahedron(), mirrored, Eigen::RowVector3d::Zero());
  for (Eigen::Index f = 4; f < 8; ++f)
    for (int k = 0; k < 3; ++k)
      if (both.F(f, k) == 4) both.F(f, k) = 0;  // share the origin
  const MeshValidation v = validate_mesh(both);
  const std::vector<DefectKind> expected = {DefectKind::non_manifold_vertex};
  CHECK(kinds(v) == expected);
  REQUIRE(v.find(DefectKind::non_manifold_vertex));
  CHECK(v.defects[0].count == 1);
  CHECK(v.defects[0].vertex == 0);
  CHECK(v.defects[0].value == 2);
  CHECK(v.unreferenced_vertices == 1);  // vertex 4, replaced by 0
}

TEST_CASE("inside-out, zero volume and nested shells") {
  MeshValidation v = validate_mesh(flipped(unit_box()));
  REQUIRE(kinds(v) == std::vector<DefectKind>{DefectKind::inside_out});
  CHECK(v.volume == -6.0);
  CHECK(v.defects[0].face == 0);
  CHECK(v.defects[0].value == -6.0);

  Mesh pillow;  // a closed, oriented, flat square: two triangulations of one square
  pillow.V.resize(4, 3);
  pillow.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  pillow.F.resize(4, 3);
  pillow.F << 0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2;
  v = validate_mesh(pillow);
  REQUIRE(kinds(v) == std::vector<DefectKind>{DefectKind::zero_volume});
  CHECK(v.genus == 0);

  const Mesh outer = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 4, 4));
  const Mesh inner = make_box(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(2, 3, 3));
  SUBCASE("two separate parts") {
    v = validate_mesh(join(outer, inner, Eigen::RowVector3d(10, 0, 0)));
    REQUIRE(kinds(v) == std::vector<DefectKind>{DefectKind::several_components});
    CHECK(v.defects[0].count == 2);
    CHECK(v.defects[0].face == 12);
    CHECK(v.component_depth == std::vector<int>({0, 0}));
    CHECK(v.volume == 64.0 + 4.0);
    CHECK(v.genus == 0);
  }
  SUBCASE("a cavity facing inwards is right") {
    v = validate_mesh(join(outer, flipped(inner), Eigen::RowVector3d::Zero()));
    REQUIRE(kinds(v) == std::vector<DefectKind>{DefectKind::several_components});
    CHECK(v.component_depth == std::vector<int>({0, 1}));
    CHECK(v.component_volume == std::vector<double>({64.0, -4.0}));
    CHECK(v.volume == 60.0);
  }
  SUBCASE("a cavity facing outwards is inside-out") {
    v = validate_mesh(join(outer, inner, Eigen::RowVector3d::Zero()));
    const Defect* d = v.find(DefectKind::inside_out);
    REQUIRE(d);
    CHECK(d->count == 1);
    CHECK(d->face == 12);
    CHECK(d->bound == 1);
  }
  SUBCASE("a cavity larger than its part: the shells cross") {
    // The slab's representative point (its first, largest face) lies outside the box, the box's
    // inside the slab: both shells face the right way for their depth, but 72.5 > 48.
    const Mesh slab = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 4, 3));
    const Mesh box = make_box(Eigen::Vector3d(0.5, 0.5, 1), Eigen::Vector3d(5.5, 5.5, 3.9));
    const Mesh crossed = join(slab, flipped(box), Eigen::RowVector3d::Zero());
    v = validate_mesh(crossed);
    CHECK(v.component_depth == std::vector<int>({0, 1}));
    CHECK(kinds(v) == std::vector<DefectKind>{DefectKind::overlapping_shells, DefectKind::several_components});
    const Defect* d = v.find(DefectKind::overlapping_shells);
    REQUIRE(d);
    CHECK(d->count == 1);
    CHECK(d->face == 12);
    CHECK(d->value == doctest::Approx(48.0 - 72.5));
    CHECK_THROWS_WITH_AS(load_raw_mesh("crossed.obj", RawMesh{MeshFormat::obj, crossed.V, crossed.F, {}, {}, {}}),
                         "crossed.obj: cavity shell encloses more than the shells around it: the signed volumes sum to -24.5 (shells cross each other), face 12",
                         MeshInputError);
    // Every face reversed: both shells are inside-out, and flipping them back (what loading does
    // for inside-out meshes) would give the same crossed shells.
    const MeshValidation reversed = validate_mesh(flipped(crossed));
    CHECK(kinds(reversed) == std::vector<DefectKind>{DefectKind::inside_out, DefectKind::overlapping_shells,
                                                     DefectKind::several_components});
    CHECK_THROWS_WITH_AS(load_raw_mesh("reversed.obj", RawMesh{MeshFormat::obj, crossed.V, flipped(crossed).F, {}, {}, {}}),
                         "reversed.obj: cavity shell encloses more than the shells around it: the signed volumes sum to "
                         "-24.5 once every face is flipped (shells cross each other), face 12",
                         MeshInputError);
  }
  SUBCASE("a part inside a cavity inside a part") {
    const Mesh core = make_box(Eigen::Vector3d(1.25, 1.5, 1.5), Eigen::Vector3d(1.75, 2.5, 2.5));
    v = validate_mesh(join(join(outer, flipped(inner), Eigen::RowVector3d::Zero()), core, Eigen::RowVector3d::Zero()));
    CHECK(kinds(v) == std::vector<DefectKind>{DefectKind::several_components});
    CHECK(v.component_depth == std::vector<int>({0, 1, 2}));
  }
}

TEST_CASE("unreferenced vertices are a note, not a defect") {
  Mesh m = unit_box();
  m.V.conservativeResize(10, 3);
  m.V.row(8) << 7, 7, 7;
  m.V.row(9) << std::numeric_limits<double>::quiet_NaN(), 0, 0;
  const MeshValidation v = validate_mesh(m);
  CHECK(v.unreferenced_vertices == 2);
  CHECK(v.first_unreferenced == 8);
  CHECK(kinds(v) == std::vector<DefectKind>{DefectKind::non_finite_coordinate});  // check reports it
  const LoadedMesh loaded = load_raw_mesh("m.obj", RawMesh{MeshFormat::obj, m.V, m.F, {}, {}, {}});
  REQUIRE(loaded.warnings.size() == 1);
  CHECK(loaded.warnings[0] == "dropped 2 unreferenced vertices (first: vertex 8)");
  CHECK(loaded.mesh.V.rows() == 8);
}

TEST_CASE("load_mesh repairs what is safe and refuses the rest, naming file faces") {
  auto raw_of = [](const Mesh& m) { return RawMesh{MeshFormat::stl_binary, m.V, m.F, {}, {}, {}}; };
  SUBCASE("inside-out is flipped with a warning, or refused on request") {
    const LoadedMesh loaded = load_raw_mesh("scan.stl", raw_of(flipped(unit_box())));
    REQUIRE(loaded.warnings.size() == 1);
    CHECK(loaded.warnings[0] == "mesh is inside-out (signed volume -6); every face flipped");
    CHECK(validate_mesh(loaded.mesh).valid());
    CHECK(validate_mesh(loaded.mesh).volume == 6.0);
    LoadOptions strict;
    strict.flip_inside_out = false;
    CHECK_THROWS_WITH_AS(load_raw_mesh("scan.stl", raw_of(flipped(unit_box())), strict),
                         "scan.stl: shell is inside-out: signed volume -6 (normals point inwards), face 0", MeshInputError);
  }
  SUBCASE("several shells: accepted with a warning unless one component is required") {
    const Mesh outer = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 4, 4));
    const Mesh hollow = join(outer, flipped(make_box(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(3, 3, 3))), Eigen::RowVector3d::Zero());
    const LoadedMesh loaded = load_raw_mesh("hollow.stl", raw_of(hollow));
    CHECK(loaded.components == 2);
    REQUIRE(loaded.warnings.size() == 1);
    CHECK(loaded.warnings[0] == "2 separate closed shells (parts or cavities); treated as one solid");
    LoadOptions single;
    single.single_component = true;
    CHECK_THROWS_WITH_AS(load_raw_mesh("hollow.stl", raw_of(hollow), single),
                         doctest::Contains("the mesh has 2 separate components, face 12; this command needs one connected surface"),
                         MeshInputError);
    // The whole hollow cube inside-out: flipping all faces fixes both shells.
    const LoadedMesh inverted = load_raw_mesh("hollow.stl", raw_of(flipped(hollow)));
    CHECK(inverted.warnings.size() == 2);
    CHECK(validate_mesh(inverted.mesh).volume == 64.0 - 8.0);
    // One part inverted, the other not: refused.
    const Mesh mixed = join(outer, flipped(outer), Eigen::RowVector3d(10, 0, 0));
    CHECK_THROWS_WITH_AS(load_raw_mesh("mixed.stl", raw_of(mixed)), doctest::Contains("flipping all faces would not fix it"),
                         MeshInputError);
  }
  SUBCASE("collapsed faces and same-orientation copies are dropped; messages keep file numbering") {
    Mesh m = unit_box();
    m = with_face(m, 0, 0, 5);  // face 12: collapsed
    m = with_face(m, 1, 2, 3);  // face 13: copy of face 1
    const LoadedMesh loaded = load_raw_mesh("fix.stl", raw_of(m));
    REQUIRE(loaded.warnings.size() == 2);
    CHECK(loaded.warnings[0] == "dropped 1 degenerate face with a repeated vertex (first: face 12)");
    CHECK(loaded.warnings[1] == "dropped 1 duplicate face (first: face 13, a copy of face 1)");
    CHECK(loaded.mesh.F.rows() == 12);
    // Drop face 0 too: the boundary left behind is reported at file face 4 (validated face 3).
    Mesh open = with_face(without_faces(unit_box(), {0}), 0, 0, 5);
    Mesh shifted = open;
    shifted.F.row(0) << 0, 0, 5;  // put the collapsed face first so file and validated numbers differ
    shifted.F.bottomRows(open.F.rows() - 1) = open.F.topRows(open.F.rows() - 1);
    const EdgeCensus census = edge_census(without_faces(shifted, {0}));
    REQUIRE(census.first_boundary_face == 0);  // box face 1 = {1, 2, 3}, file face 1
    CHECK_THROWS_WITH_AS(load_raw_mesh("open.stl", raw_of(shifted)),
                         "open.stl: the mesh is not closed: edge 1-2 belongs to one face only, face 1 (3 edges in all)",
                         MeshInputError);
  }
  SUBCASE("text formats name the line") {
    Mesh m = without_faces(unit_box(), {11});
    RawMesh raw{MeshFormat::obj, m.V, m.F, {}, {}, {}};
    for (int i = 0; i < 8; ++i) raw.vertex_line.push_back(i + 1);
    for (int f = 0; f < 11; ++f) raw.face_line.push_back(f + 20);
    const EdgeCensus census = edge_census(m);
    REQUIRE(census.first_boundary_face == 3);  // box face 3 = {5, 7, 6} lost its neighbour across 5-7
    CHECK_THROWS_WITH_AS(load_raw_mesh("open.obj", raw),
                         "open.obj:23: the mesh is not closed: edge 5-7 belongs to one face only (3 edges in all)",
                         MeshInputError);
  }
  SUBCASE("opposite duplicates and bad indices are refused") {
    Mesh m = with_face(unit_box(), 1, 3, 2);  // face 12: face 1 reversed
    CHECK_THROWS_WITH_AS(load_raw_mesh("dup.stl", raw_of(m)),
                         "dup.stl: face repeats the vertices of face 1 (opposite orientation), face 12", MeshInputError);
    m = unit_box();
    m.F(3, 1) = 99;
    CHECK_THROWS_WITH_AS(load_raw_mesh("idx.stl", raw_of(m)),
                         "idx.stl: vertex index 99 (counting from 0) is out of range: the mesh has 8 vertices, face 3",
                         MeshInputError);
  }
}
