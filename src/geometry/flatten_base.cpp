#include "geometry/flatten_base.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "geometry/triangulate_polygons.h"

namespace offsetopt {

std::string FlattenSettings::check() const {
  if (!(height > 0.0) || !std::isfinite(height)) return "the base height must be a finite number > 0";
  return {};
}

FlattenResult flatten_base(const Mesh& mesh, const FlattenSettings& settings) {
  FlattenResult result;
  if (const std::string problem = settings.check(); !problem.empty()) {
    result.status = FlattenStatus::bad_settings;
    result.message = problem;
    return result;
  }
  const Eigen::Index nv = mesh.V.rows();
  if (nv == 0 || mesh.F.rows() == 0) {
    result.status = FlattenStatus::bad_settings;
    result.message = "empty mesh";
    return result;
  }
  const double zmin = mesh.V.col(2).minCoeff(), zmax = mesh.V.col(2).maxCoeff();
  std::vector<double> heights(mesh.V.col(2).data(), mesh.V.col(2).data() + nv);
  std::sort(heights.begin(), heights.end());
  double plane = zmin + settings.height;
  // The symbolic rule: a plane through vertices moves down past them (they count as above).
  for (Eigen::Index step = 0; step <= nv && std::binary_search(heights.begin(), heights.end(), plane); ++step)
    plane = std::nextafter(plane, -std::numeric_limits<double>::infinity());
  if (!(plane < zmax)) {
    result.status = FlattenStatus::cuts_everything;
    result.message = "the base height " + std::to_string(settings.height) + " reaches the top of the mesh (height " +
                     std::to_string(zmax - zmin) + ")";
    return result;
  }
  if (!(plane > zmin) || std::binary_search(heights.begin(), heights.end(), plane)) {
    result.status = FlattenStatus::bad_settings;
    result.message = "the base height is too small to cut anything";
    return result;
  }
  result.plane_z = plane;

  std::vector<int> new_index(static_cast<std::size_t>(nv), -1);
  std::vector<Eigen::Vector3d> points;
  for (Eigen::Index v = 0; v < nv; ++v)
    if (mesh.V(v, 2) > plane) {
      new_index[v] = static_cast<int>(points.size());
      points.emplace_back(mesh.V.row(v).transpose());
    }
  result.removed_vertices = static_cast<int>(nv) - static_cast<int>(points.size());
  const int first_crossing = static_cast<int>(points.size());

  // One point per cut edge, interpolated from its lower end so both faces get the same double.
  std::map<std::pair<int, int>, int> crossing_of_edge;
  auto crossing = [&](int u, int w) {
    const int below = mesh.V(u, 2) < plane ? u : w, above = below == u ? w : u;
    const auto key = std::make_pair(std::min(u, w), std::max(u, w));
    auto it = crossing_of_edge.find(key);
    if (it != crossing_of_edge.end()) return it->second;
    const Eigen::Vector3d lo = mesh.V.row(below).transpose(), hi = mesh.V.row(above).transpose();
    const double t = (plane - lo.z()) / (hi.z() - lo.z());
    const Eigen::Vector3d x(lo.x() + t * (hi.x() - lo.x()), lo.y() + t * (hi.y() - lo.y()), plane);
    const int id = static_cast<int>(points.size());
    points.push_back(x);
    crossing_of_edge.emplace(key, id);
    return id;
  };

  std::vector<std::array<int, 3>> faces;
  std::map<int, int> next_on_cut;  // directed boundary edges of the kept surface on the plane
  bool manifold = true;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    int polygon[4], is_crossing[4], size = 0;
    for (int k = 0; k < 3; ++k) {
      const int u = mesh.F(f, k), w = mesh.F(f, (k + 1) % 3);
      const bool u_above = mesh.V(u, 2) > plane, w_above = mesh.V(w, 2) > plane;
      if (u_above) polygon[size] = new_index[u], is_crossing[size++] = 0;
      if (u_above != w_above) polygon[size] = crossing(u, w), is_crossing[size++] = 1;
    }
    if (size == 3 && !is_crossing[0] && !is_crossing[1] && !is_crossing[2]) {
      faces.push_back({polygon[0], polygon[1], polygon[2]});
      continue;
    }
    if (size == 0) continue;
    for (int k = 0; k < size; ++k)
      if (is_crossing[k] && is_crossing[(k + 1) % size])
        if (!next_on_cut.emplace(polygon[k], polygon[(k + 1) % size]).second) manifold = false;
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
  const int crossings = static_cast<int>(points.size()) - first_crossing;
  result.cut_edges = crossings;
  if (!manifold || static_cast<int>(next_on_cut.size()) != crossings) {
    result.status = FlattenStatus::cap_failed;
    result.message = "the cut does not close into loops (is the mesh closed and manifold?)";
    return result;
  }

  // Chain the cut edges into loops (each crossing has one successor and one predecessor).
  std::vector<char> visited(static_cast<std::size_t>(crossings), 0);
  std::vector<int> loop_point;  // global triangulation index -> mesh vertex
  for (int start = first_crossing; start < first_crossing + crossings; ++start) {
    if (visited[start - first_crossing]) continue;
    std::vector<Eigen::Vector2d> loop;
    int p = start;
    for (int step = 0; step <= crossings; ++step) {
      if (visited[p - first_crossing]) break;
      visited[p - first_crossing] = 1;
      loop.emplace_back(points[p].x(), points[p].y());
      loop_point.push_back(p);
      const auto it = next_on_cut.find(p);
      if (it == next_on_cut.end()) break;
      p = it->second;
    }
    if (p != start) {
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
