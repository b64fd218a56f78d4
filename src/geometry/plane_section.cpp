// Plane sections of closed triangle meshes; see plane_section.h for the symbolic rule and the
// orientation. Worked case for the orientation: a face with outward normal +x cut by z = 0 seen
// from +z runs in +y (m × n), and walking the face counter-clockwise its edge leaving the
// positive side comes before the edge entering it: the segment goes from the first to the second.
#include "geometry/plane_section.h"

#include <map>
#include <utility>

namespace offsetopt {

SectionPlane xz_plane(double y0) {
  SectionPlane p;
  p.normal = Eigen::Vector3d(0.0, -1.0, 0.0);
  p.offset = -y0;
  p.u = Eigen::Vector3d::UnitX();
  p.v = Eigen::Vector3d::UnitZ();
  return p;
}

SectionPlane yz_plane(double x0) {
  SectionPlane p;
  p.normal = Eigen::Vector3d::UnitX();
  p.offset = x0;
  p.u = Eigen::Vector3d::UnitY();
  p.v = Eigen::Vector3d::UnitZ();
  return p;
}

SectionPlane xy_plane(double z0) {
  SectionPlane p;
  p.normal = Eigen::Vector3d::UnitZ();
  p.offset = z0;
  p.u = Eigen::Vector3d::UnitX();
  p.v = Eigen::Vector3d::UnitY();
  return p;
}

namespace {

using EdgeKey = std::pair<int, int>;  // (lower vertex index, higher)

EdgeKey edge_key(int a, int b) { return a < b ? EdgeKey(a, b) : EdgeKey(b, a); }

struct Segment {
  EdgeKey from, to;
};

}  // namespace

PlaneSection plane_section(const Mesh& mesh, const SectionPlane& plane) {
  PlaneSection section;
  const Eigen::Index n = mesh.V.rows();
  std::vector<double> value(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i)
    value[static_cast<std::size_t>(i)] = plane.normal.dot(mesh.V.row(i).transpose()) - plane.offset;
  auto positive = [&](int i) { return value[static_cast<std::size_t>(i)] >= 0.0; };  // 0 counts as +

  std::vector<Segment> segments;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int c[3] = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
    EdgeKey leaving{-1, -1}, entering{-1, -1};
    for (int e = 0; e < 3; ++e) {
      const int a = c[e], b = c[(e + 1) % 3];
      if (positive(a) && !positive(b)) leaving = edge_key(a, b);
      if (!positive(a) && positive(b)) entering = edge_key(a, b);
    }
    if (leaving.first >= 0 && entering.first >= 0) segments.push_back({leaving, entering});
  }

  // Each crossed edge leaves one face and enters its neighbour: index the segments by the edge
  // they start on (an ordered map: no hash order reaches the output).
  std::map<EdgeKey, int> starting_at;
  for (std::size_t s = 0; s < segments.size(); ++s) starting_at.emplace(segments[s].from, static_cast<int>(s));

  // Measured from the endpoint on the positive side: the same bits for both faces of the edge and
  // for any numbering of the vertices (a file read back may drop unused vertices).
  auto crossing = [&](const EdgeKey& key) {
    int from = key.first, to = key.second;
    if (!positive(from)) std::swap(from, to);
    const double va = value[static_cast<std::size_t>(from)], vb = value[static_cast<std::size_t>(to)];
    const Eigen::Vector3d a = mesh.V.row(from).transpose(), b = mesh.V.row(to).transpose();
    const double t = va / (va - vb);  // va >= 0 > vb
    const Eigen::Vector3d p = a + t * (b - a);
    return Eigen::Vector2d(plane.u.dot(p), plane.v.dot(p));
  };

  std::vector<char> used(segments.size(), 0);
  for (std::size_t first = 0; first < segments.size(); ++first) {
    if (used[first]) continue;
    SectionLoop loop;
    std::size_t s = first;
    // At most one step per segment: a closed mesh returns to `first`, anything else stops.
    for (std::size_t step = 0; step <= segments.size(); ++step) {
      used[s] = 1;
      loop.points.push_back(crossing(segments[s].from));
      const auto next = starting_at.find(segments[s].to);
      if (next == starting_at.end()) {
        loop.points.push_back(crossing(segments[s].to));
        loop.closed = false;
        break;
      }
      s = static_cast<std::size_t>(next->second);
      if (s == first) break;
      if (used[s]) {
        loop.closed = false;
        break;
      }
    }
    if (!loop.closed) section.status = SectionStatus::open_chain;
    double twice_area = 0.0;
    for (std::size_t i = 0; i < loop.points.size(); ++i) {
      const Eigen::Vector2d& p = loop.points[i];
      const Eigen::Vector2d& q = loop.points[(i + 1) % loop.points.size()];
      twice_area += p.x() * q.y() - q.x() * p.y();
    }
    loop.signed_area = 0.5 * twice_area;
    section.loops.push_back(std::move(loop));
  }
  return section;
}

}  // namespace offsetopt
