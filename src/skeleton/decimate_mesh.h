// A coarse copy of a closed triangle mesh for the coarse-to-fine contraction
// (skeleton/laplacian_contraction.h): quadric-error half-edge collapses (Garland & Heckbert 1997,
// "Surface Simplification Using Quadric Error Metrics", with the collapse target restricted to
// the edge's other end), so every coarse vertex is an input vertex at its input position.
//
// A collapse u -> v removes u and the two faces on the edge; it is costed by the summed
// area-weighted plane quadrics Q_u + Q_v evaluated at x_v, and taken only when
//   - the edge has exactly two faces and the one-rings of u and v share exactly their two
//     opposite vertices (the link condition: the surface stays a closed 2-manifold),
//   - no moved face turns by more than acos(min_normal_cosine) or becomes a sliver (compactness
//     below min_compactness where it was above it).
// The collapses are made in rounds: each round sorts the cheapest quarter of the edges by cost
// (ties by vertex indices) and walks them in that order, and a collapse blocks the one-ring it
// leaves around v for the rest of the round, so every collapse taken has the cost it was sorted
// by and the result is a function of the mesh alone. (One global heap gave the same quality at
// twice the time, its cost in cache misses: 17 s of a 10^6-vertex run.)
#pragma once
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

struct DecimateOptions {
  double min_normal_cosine = 0.2;
  // 4 sqrt(3) area / (sum of squared edge lengths): 1 for an equilateral triangle.
  double min_compactness = 0.05;
};

struct DecimatedMesh {
  Mesh mesh;                     // the coarse mesh: vertices are input vertices, faces renumbered
  std::vector<int> input_vertex;  // coarse vertex -> the input vertex it is (increasing)
  std::vector<int> coarse_vertex; // input vertex -> its coarse vertex, or -1 when collapsed
};

// Collapses until at most `target_vertices` remain or no allowed collapse is left. Faces must be
// valid indices; a mesh with boundary edges keeps its boundary vertices.
DecimatedMesh decimate_mesh(const Vertices& V, const Faces& F, int target_vertices, const DecimateOptions& options = {});

}  // namespace offsetopt
