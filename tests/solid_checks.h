// Mass properties and support polygon of a written solid, computed for the tests without the
// tool's code: volume integrals by the divergence theorem over the tetrahedra each face spans
// with a point near the solid (shells split by shared vertices, the positive ones the outer
// surface), and the support polygon as a monotone-chain hull of the lowest vertices' xy.
#pragma once
#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mesh/mesh.h"

namespace offsetopt::test {

struct Integrals {
  double volume = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   // ∫ (x - origin)
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // ∫ (x - origin)(x - origin)^T
};

inline void add_tetrahedron(Integrals& in, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double v = a.dot(b.cross(c)) / 6.0;
  const Eigen::Vector3d sum = a + b + c;
  in.volume += v;
  in.first += v * sum / 4.0;
  in.second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
}

// Every face's tetrahedron with `origin`, summed.
inline Integrals integrals_of(const Mesh& mesh, const Eigen::Vector3d& origin) {
  Integrals out;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    add_tetrahedron(out, mesh.V.row(mesh.F(f, 0)).transpose() - origin, mesh.V.row(mesh.F(f, 1)).transpose() - origin,
                    mesh.V.row(mesh.F(f, 2)).transpose() - origin);
  return out;
}

inline Integrals minus(Integrals a, const Integrals& b) {
  a.volume -= b.volume;
  a.first -= b.first;
  a.second -= b.second;
  return a;
}

// Mass (density 1), centre of mass and the inertia tensor about it, of integrals measured from
// `origin`: I = tr(S) 1 - S with S = ∫ (x - c)(x - c)^T.
struct MassFigures {
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

inline MassFigures mass_figures(const Integrals& in, const Eigen::Vector3d& origin) {
  MassFigures m;
  m.mass = in.volume;
  const Eigen::Vector3d d = in.first / in.volume;
  m.com = origin + d;
  const Eigen::Matrix3d S = in.second - in.volume * d * d.transpose();
  m.inertia = S.trace() * Eigen::Matrix3d::Identity() - S;
  return m;
}

struct SolidFigures {
  Eigen::Vector3d origin;
  Integrals solid, outer;  // all shells; the shells of positive volume (the outer surface)
};

inline SolidFigures measure_solid(const Mesh& mesh) {
  SolidFigures out;
  out.origin = 0.5 * (mesh.V.colwise().minCoeff() + mesh.V.colwise().maxCoeff()).transpose();
  std::vector<int> parent(static_cast<std::size_t>(mesh.V.rows()));
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  std::function<int(int)> root = [&](int v) { return parent[v] == v ? v : parent[v] = root(parent[v]); };
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 1; k < 3; ++k) parent[root(mesh.F(f, k))] = root(mesh.F(f, 0));
  std::map<int, Integrals> shells;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = mesh.V.row(mesh.F(f, k)).transpose() - out.origin;
    add_tetrahedron(out.solid, p[0], p[1], p[2]);
    add_tetrahedron(shells[root(mesh.F(f, 0))], p[0], p[1], p[2]);
  }
  for (const auto& entry : shells)
    if (entry.second.volume > 0.0) {
      out.outer.volume += entry.second.volume;
      out.outer.first += entry.second.first;
      out.outer.second += entry.second.second;
    }
  return out;
}

// How far `point` lies inside the convex hull of the xy of the vertices within ground_tol of the
// lowest one (negative outside; -infinity for fewer than three hull corners).
inline double support_margin(const Mesh& mesh, double ground_tol, const Eigen::Vector2d& point) {
  const double zmin = mesh.V.col(2).minCoeff();
  std::vector<Eigen::Vector2d> contacts;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (mesh.V(v, 2) <= zmin + ground_tol) contacts.emplace_back(mesh.V(v, 0), mesh.V(v, 1));
  std::sort(contacts.begin(), contacts.end(),
            [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t start = hull.size();
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      const Eigen::Vector2d& p = pass == 0 ? contacts[i] : contacts[contacts.size() - 1 - i];
      while (hull.size() >= start + 2 && turn(hull[hull.size() - 2], hull.back(), p) <= 0.0) hull.pop_back();
      hull.push_back(p);
    }
    hull.pop_back();
  }
  if (hull.size() < 3) return -std::numeric_limits<double>::infinity();
  double margin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d a = hull[i], b = hull[(i + 1) % hull.size()];
    margin = std::min(margin, turn(a, b, point) / (b - a).norm());  // counter-clockwise: left is inside
  }
  return margin;
}

}  // namespace offsetopt::test
