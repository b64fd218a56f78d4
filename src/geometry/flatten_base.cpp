#include "geometry/flatten_base.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "geometry/triangulate_polygons.h"
#include "util/det_math.h"
#include "util/format_double.h"

namespace offsetopt {

std::string FlattenOptions::check() const {
  if (!(height > 0.0) || !std::isfinite(height)) return "the base height must be a finite number > 0";
  if (!(snap >= 0.0 && snap < 1e-3)) return "snap must be in [0, 1e-3)";
  return {};
}

FlattenResult flatten_base(const Mesh& mesh, const FlattenOptions& settings) {
  FlattenResult result;
  if (const std::string problem = settings.check(); !problem.empty()) {
    result.status = FlattenStatus::bad_options;
    result.message = problem;
    return result;
  }
  const Eigen::Index nv = mesh.V.rows();
  if (nv == 0 || mesh.F.rows() == 0) {
    result.status = FlattenStatus::bad_options;
    result.message = "empty mesh";
    return result;
  }
  const double zmin = mesh.V.col(2).minCoeff(), zmax = mesh.V.col(2).maxCoeff();
  const double plane = zmin + settings.height;
  if (!(plane < zmax)) {
    result.status = FlattenStatus::cuts_everything;
    result.message = "the base height " + format_double(settings.height) + " reaches the top of the mesh (height " +
                     format_double(zmax - zmin) + ")";
    return result;
  }
  if (!(plane > zmin + 2.0 * settings.snap * (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm())) {
    result.status = FlattenStatus::bad_options;
    result.message = "the base height is too small to cut anything";
    return result;
  }
  result.plane_z = plane;

  // Vertices a hair off the plane are put on it first: a cut passing 1e-15 from a vertex would
  // leave triangles of no area in double arithmetic next to it.
  const double diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  const double snap = settings.snap * diagonal;
  Eigen::VectorXd z = mesh.V.col(2);
  for (Eigen::Index v = 0; v < nv; ++v)
    if (z[v] != plane && std::fabs(z[v] - plane) <= snap) {
      z[v] = plane;
      ++result.snapped_vertices;
    }
  // Kept: strictly above the plane, or on it (the symbolic rule).
  auto kept = [&](int v) { return !(z[v] < plane); };
  std::vector<int> new_index(static_cast<std::size_t>(nv), -1);
  std::vector<Eigen::Vector3d> points;
  for (Eigen::Index v = 0; v < nv; ++v)
    if (kept(static_cast<int>(v))) {
      new_index[v] = static_cast<int>(points.size());
      points.emplace_back(mesh.V(v, 0), mesh.V(v, 1), z[v]);
    }
  result.removed_vertices = static_cast<int>(nv) - static_cast<int>(points.size());

  // The cut point of an edge from below to kept: the kept end itself when it is on the plane (the
  // limit of a plane slightly below it), else one new point per edge, interpolated from the lower
  // end so both faces get the same doubles.
  std::map<std::pair<int, int>, int> crossing_of_edge;
  auto crossing = [&](int u, int w) {
    const int below = kept(u) ? w : u, above = below == u ? w : u;
    if (z[above] == plane) return new_index[above];
    const auto key = std::make_pair(std::min(u, w), std::max(u, w));
    auto it = crossing_of_edge.find(key);
    if (it != crossing_of_edge.end()) return it->second;
    const Eigen::Vector3d lo(mesh.V(below, 0), mesh.V(below, 1), z[below]), hi(mesh.V(above, 0), mesh.V(above, 1), z[above]);
    const double t = (plane - lo.z()) / (hi.z() - lo.z());
    const Eigen::Vector3d x(lo.x() + t * (hi.x() - lo.x()), lo.y() + t * (hi.y() - lo.y()), plane);
    const int id = static_cast<int>(points.size());
    points.push_back(x);
    crossing_of_edge.emplace(key, id);
    return id;
  };

  std::vector<std::array<int, 3>> faces;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    int polygon[4], size = 0;
    for (int k = 0; k < 3; ++k) {
      const int u = mesh.F(f, k), w = mesh.F(f, (k + 1) % 3);
      // A cut at a vertex on the plane repeats it: keep one copy.
      if (kept(u) && (size == 0 || polygon[size - 1] != new_index[u])) polygon[size++] = new_index[u];
      if (kept(u) != kept(w)) {
        const int x = crossing(u, w);
        if (size == 0 || polygon[size - 1] != x) polygon[size++] = x;
      }
    }
    if (size > 1 && polygon[size - 1] == polygon[0]) --size;  // cut at a vertex on the plane
    if (size < 3) continue;  // nothing of it above the plane
    if (size == 3) {
      faces.push_back({polygon[0], polygon[1], polygon[2]});
    } else {
      // A quad: split along its shorter diagonal (better shaped triangles).
      const double d02 = (points[polygon[0]] - points[polygon[2]]).squaredNorm();
      const double d13 = (points[polygon[1]] - points[polygon[3]]).squaredNorm();
      if (d02 <= d13) {
        faces.push_back({polygon[0], polygon[1], polygon[2]});
        faces.push_back({polygon[0], polygon[2], polygon[3]});
      } else {
        faces.push_back({polygon[0], polygon[1], polygon[3]});
        faces.push_back({polygon[1], polygon[2], polygon[3]});
      }
    }
  }
  // The kept surface's boundary: directed edges in the plane without their reverse.
  std::map<std::pair<int, int>, int> in_plane_edges;
  for (const auto& t : faces)
    for (int k = 0; k < 3; ++k) {
      const int u = t[k], w = t[(k + 1) % 3];
      if (points[u].z() == plane && points[w].z() == plane) ++in_plane_edges[{u, w}];
    }
  // Cut edges by start point. A vertex on the plane where the section touches itself (a saddle
  // tangent to the plane) starts two of them.
  std::map<int, std::vector<int>> cut_edges_from;
  std::map<int, int> in_degree;
  bool manifold = true;
  int edge_count = 0;
  for (const auto& [edge, count] : in_plane_edges) {
    if (count != 1) manifold = false;
    if (in_plane_edges.count({edge.second, edge.first}) != 0) continue;
    cut_edges_from[edge.first].push_back(edge.second);
    ++in_degree[edge.second];
    ++edge_count;
  }
  for (const auto& [point, targets] : cut_edges_from)
    if (in_degree[point] != static_cast<int>(targets.size())) manifold = false;
  result.cut_edges = edge_count;
  if (!manifold || in_degree.size() != cut_edges_from.size()) {
    result.status = FlattenStatus::cap_failed;
    result.message = "the cut does not close into loops (is the mesh closed and manifold?)";
    return result;
  }

  // Chain the cut edges into loops. Where a point starts several, take the sharpest left turn:
  // the loops then touch there without crossing, each one simple.
  std::map<std::pair<int, int>, char> used;
  std::vector<int> loop_point;  // global triangulation index -> point
  auto turn_left = [&](int from, int at, int to) {
    const Eigen::Vector2d d = (points[at] - points[from]).head<2>(), e = (points[to] - points[at]).head<2>();
    return det_atan2(d.x() * e.y() - d.y() * e.x(), d.x() * e.x() + d.y() * e.y());
  };
  for (const auto& [first, targets] : cut_edges_from)
    for (int second : targets) {
      if (used[{first, second}]) continue;
      std::vector<Eigen::Vector2d> loop;
      int from = first, at = second;
      used[{first, second}] = 1;
      loop.emplace_back(points[first].x(), points[first].y());
      loop_point.push_back(first);
      for (int step = 0; step <= edge_count && at != first; ++step) {
        loop.emplace_back(points[at].x(), points[at].y());
        loop_point.push_back(at);
        int next = -1;
        double best = 0.0;
        for (int candidate : cut_edges_from[at]) {
          if (used[{at, candidate}]) continue;
          const double turn = turn_left(from, at, candidate);
          if (next < 0 || turn > best) next = candidate, best = turn;
        }
        if (next < 0) break;
        used[{at, next}] = 1;
        from = at;
        at = next;
      }
      if (at != first) {
        result.status = FlattenStatus::cap_failed;
        result.message = "a cut polygon does not close (is the mesh closed and manifold?)";
        return result;
      }
      result.loops.push_back(std::move(loop));
    }
  const PolygonTriangulation cap = triangulate_polygons(result.loops);
  if (cap.status != TriangulationStatus::ok) {
    result.status = FlattenStatus::cap_failed;
    result.message = "the cut polygons could not be triangulated: " + cap.message;
    return result;
  }
  result.cap_loops = static_cast<int>(result.loops.size());
  result.cap_holes = cap.holes;
  result.cap_faces = static_cast<int>(cap.triangles.size());
  // Counter-clockwise seen from above is +z; the cap faces −z, so each triangle is reversed.
  for (const auto& t : cap.triangles) faces.push_back({loop_point[t[0]], loop_point[t[2]], loop_point[t[1]]});

  result.mesh.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) result.mesh.V.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  result.mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i)
    result.mesh.F.row(static_cast<Eigen::Index>(i)) << faces[i][0], faces[i][1], faces[i][2];
  return result;
}

}  // namespace offsetopt
