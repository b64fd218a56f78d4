#include "mesh/primitives.h"

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>

#include "util/det_math.h"

namespace offsetopt {

namespace {

Mesh from_lists(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<int, 3>>& faces) {
  Mesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) mesh.V.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose();
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (int c = 0; c < 3; ++c) mesh.F(static_cast<Eigen::Index>(i), c) = faces[i][static_cast<std::size_t>(c)];
  return mesh;
}

}  // namespace

Mesh make_icosphere(double radius, int subdivisions) {
  if (subdivisions < 0 || subdivisions > 9) throw std::invalid_argument("make_icosphere: subdivisions must be in [0, 9]");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {
      {-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
      {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {
      {0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
      {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back(((v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]) * 0.5).normalized());
      const int index = static_cast<int>(v.size()) - 1;
      midpoint.emplace(key, index);
      return index;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(f.size() * 4);
    for (const auto& tri : f) {
      const int a = mid(tri[0], tri[1]), b = mid(tri[1], tri[2]), c = mid(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    f.swap(next);
  }
  for (auto& p : v) p *= radius;
  return from_lists(v, f);
}

Mesh make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i < 8; ++i)
    v.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  const std::vector<std::array<int, 3>> f = {
      {0, 2, 1}, {1, 2, 3},   // z = lo
      {4, 5, 6}, {5, 7, 6},   // z = hi
      {0, 1, 4}, {1, 5, 4},   // y = lo
      {2, 6, 3}, {3, 6, 7},   // y = hi
      {0, 4, 2}, {2, 4, 6},   // x = lo
      {1, 3, 5}, {3, 7, 5}};  // x = hi
  return from_lists(v, f);
}

Mesh make_torus(double major_radius, double minor_radius, int major_segments, int minor_segments) {
  if (major_segments < 3 || minor_segments < 3) throw std::invalid_argument("make_torus: need at least 3 segments each way");
  std::vector<Eigen::Vector3d> v;
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i < major_segments; ++i) {
    double su, cu;
    det_sincos(2.0 * kPi * i / major_segments, su, cu);
    for (int j = 0; j < minor_segments; ++j) {
      double sv, cv;
      det_sincos(2.0 * kPi * j / minor_segments, sv, cv);
      const double ring = major_radius + minor_radius * cv;
      v.emplace_back(ring * cu, ring * su, minor_radius * sv);
    }
  }
  auto id = [&](int i, int j) { return (i % major_segments) * minor_segments + (j % minor_segments); };
  for (int i = 0; i < major_segments; ++i)
    for (int j = 0; j < minor_segments; ++j) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      f.push_back({a, b, c});
      f.push_back({a, c, d});
    }
  return from_lists(v, f);
}

Mesh make_revolution(const std::vector<std::pair<double, double>>& profile, int segments) {
  if (segments < 3) throw std::invalid_argument("make_revolution: need at least 3 segments");
  if (profile.size() < 3) throw std::invalid_argument("make_revolution: profile needs two poles and a ring");
  if (profile.front().first != 0.0 || profile.back().first != 0.0)
    throw std::invalid_argument("make_revolution: profile must start and end on the axis");
  const int rings = static_cast<int>(profile.size()) - 2;
  for (int j = 1; j <= rings; ++j)
    if (!(profile[static_cast<std::size_t>(j)].first > 0.0)) throw std::invalid_argument("make_revolution: inner profile radii must be > 0");

  std::vector<Eigen::Vector3d> v;
  std::vector<std::array<int, 3>> f;
  v.emplace_back(0.0, 0.0, profile.front().second);
  std::vector<double> sines(static_cast<std::size_t>(segments)), cosines(static_cast<std::size_t>(segments));
  for (int i = 0; i < segments; ++i)
    det_sincos(2.0 * kPi * i / segments, sines[static_cast<std::size_t>(i)], cosines[static_cast<std::size_t>(i)]);
  for (int j = 1; j <= rings; ++j) {
    const auto [r, z] = profile[static_cast<std::size_t>(j)];
    for (int i = 0; i < segments; ++i)
      v.emplace_back(r * cosines[static_cast<std::size_t>(i)], r * sines[static_cast<std::size_t>(i)], z);
  }
  const int top = static_cast<int>(v.size());
  v.emplace_back(0.0, 0.0, profile.back().second);

  auto id = [&](int ring, int i) { return 1 + (ring - 1) * segments + (i % segments); };
  for (int i = 0; i < segments; ++i) f.push_back({0, id(1, i + 1), id(1, i)});
  for (int j = 1; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const int a = id(j, i), b = id(j, i + 1), c = id(j + 1, i + 1), d = id(j + 1, i);
      f.push_back({a, b, c});
      f.push_back({a, c, d});
    }
  for (int i = 0; i < segments; ++i) f.push_back({top, id(rings, i), id(rings, i + 1)});
  return from_lists(v, f);
}

Mesh make_capsule(double radius, double half_length, int segments, int cap_rings, int body_rings) {
  if (cap_rings < 1 || body_rings < 1) throw std::invalid_argument("make_capsule: need at least one ring per part");
  std::vector<std::pair<double, double>> profile;
  profile.emplace_back(0.0, -half_length - radius);
  for (int k = 1; k <= cap_rings; ++k) {  // bottom hemisphere, polar angle from the pole to the equator
    double s, c;
    det_sincos(0.5 * kPi * k / cap_rings, s, c);
    profile.emplace_back(radius * s, -half_length - radius * c);
  }
  for (int k = 1; k < body_rings; ++k)
    profile.emplace_back(radius, -half_length + 2.0 * half_length * k / body_rings);
  for (int k = cap_rings; k >= 1; --k) {
    double s, c;
    det_sincos(0.5 * kPi * k / cap_rings, s, c);
    profile.emplace_back(radius * s, half_length + radius * c);
  }
  profile.emplace_back(0.0, half_length + radius);
  return make_revolution(profile, segments);
}

Mesh make_cylinder(double radius, double z0, double z1, int segments, int body_rings, int cap_rings) {
  if (cap_rings < 1 || body_rings < 1) throw std::invalid_argument("make_cylinder: need at least one ring per part");
  std::vector<std::pair<double, double>> profile;
  profile.emplace_back(0.0, z0);
  for (int k = 1; k <= cap_rings; ++k) profile.emplace_back(radius * k / cap_rings, z0);
  for (int k = 1; k < body_rings; ++k) profile.emplace_back(radius, z0 + (z1 - z0) * k / body_rings);
  for (int k = cap_rings; k >= 1; --k) profile.emplace_back(radius * k / cap_rings, z1);
  profile.emplace_back(0.0, z1);
  return make_revolution(profile, segments);
}

}  // namespace offsetopt
