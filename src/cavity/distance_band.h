// Which of a few distance thresholds each point of a grid keeps from a triangle surface: the
// carvable cells' test (cavity/carvable_cells.h) of whether a node or a cell centre is at least a
// wall (or a wall less half a cell, or the outer band's width) away from the surface.
#pragma once
#include <cstdint>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/node_grid.h"

namespace offsetopt {

// by_points: one capped closest-point query per block of 4³ points; its centre's distance D and
//   closest point q bound every point's distance, d(p) >= D − |p − c| and d(p) <= min(D + |p − c|,
//   |p − q|), which settle most points (all of a block no threshold comes near). A 2³ sub-block
//   with points left open gathers the faces that can be nearest to any of its points (within
//   u + 2 r2 of its centre c2, u bounding d(c2), r2 its half diagonal; or within top + r2 when
//   that is less: a point with no face that near reaches every threshold), and each open point's
//   distance is the least over them. Every margin is 1e-9 of the spacing, far above the computed
//   distances' errors; a distance within it of a threshold is decided by face_within itself.
// by_faces: every face measures the points of its box grown by the largest threshold, and each
//   point keeps its least squared distance (one double per grid point, 32 MB at 2^22 points).
//   Cheaper where the faces are few against the points (the demo meshes: 20% fewer instructions),
//   far dearer where they are many (a scan on the same grid).
// automatic: by_faces on a grid of at most 2^22 points when its point-face tests number at most
//   8.5 per masked point, else by_points.
enum class BandMethod { automatic, by_points, by_faces };

// Per point of `g` where mask != 0: how many of the ascending `thresholds` its unsigned distance
// to the surface of `bvh` reaches (d >= t, exactly as face_within(bvh, p, t, true) decides it), so
// every method gives the same counts; 0 where mask == 0. `queries` grows by the points whose
// distance by_points measured one by one. The same result for any `threads` (>= 1).
std::vector<std::int8_t> distance_band(const NodeGrid& g, const std::vector<std::int8_t>& mask, const TriangleBvh& bvh,
                                       const std::vector<double>& thresholds, int threads, std::int64_t& queries,
                                       BandMethod method = BandMethod::automatic);

}  // namespace offsetopt
