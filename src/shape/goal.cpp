#include "shape/goal.h"

#include <cstring>

#include "util/dual.h"

namespace offsetopt {

namespace {

using D = Dual<20>;

struct Properties {
  D m, cx, cy, cz, Ixx, Iyy, Izz, Ixy, Iyz, Izx;
};

// Mass properties of the solid whose raw integrals are `f` (docs/design.md convention).
Properties properties_of(const D* f) {
  Properties p;
  p.m = f[kIntVolume];
  p.cx = f[kIntX] / p.m;
  p.cy = f[kIntY] / p.m;
  p.cz = f[kIntZ] / p.m;
  const D sxx = f[kIntXX] - p.m * p.cx * p.cx, syy = f[kIntYY] - p.m * p.cy * p.cy, szz = f[kIntZZ] - p.m * p.cz * p.cz;
  const D sxy = f[kIntXY] - p.m * p.cx * p.cy, syz = f[kIntYZ] - p.m * p.cy * p.cz, szx = f[kIntZX] - p.m * p.cz * p.cx;
  p.Ixx = syy + szz;
  p.Iyy = sxx + szz;
  p.Izz = sxx + syy;
  p.Ixy = -sxy;
  p.Iyz = -syz;
  p.Izx = -szx;
  return p;
}

struct Rows {
  std::vector<D> equality, inequality;
};

D stand_objective(const Properties& p) { return p.cx * p.cx + p.cy * p.cy + p.cz; }

void add_support_rows(const GoalSpec& spec, const Properties& p, Rows& rows) {
  const std::size_t n = spec.support_polygon.size();
  for (std::size_t e = 0; e < n; ++e) {
    const Eigen::Vector2d a = spec.support_polygon[e], b = spec.support_polygon[(e + 1) % n];
    const Eigen::Vector2d edge = b - a;
    const Eigen::Vector2d inward = Eigen::Vector2d(-edge.y(), edge.x()) / edge.norm();  // left of a CCW edge
    const D inside = (p.cx - a.x()) * inward.x() + (p.cy - a.y()) * inward.y();
    rows.inequality.push_back(spec.margin - inside);
  }
  rows.inequality.push_back(-p.cz);
}

D spin_ratio_term(const Properties& p) {
  // Eigenvalues of the xy block [[Ixx, Ixy], [Ixy, Iyy]] (paper, after eq. 8).
  const D root = sqrt((p.Ixx - p.Iyy) * (p.Ixx - p.Iyy) + 4.0 * p.Ixy * p.Ixy);
  const D ia = 0.5 * (p.Ixx + p.Iyy - root), ib = 0.5 * (p.Ixx + p.Iyy + root);
  return (ia / p.Izz) * (ia / p.Izz) + (ib / p.Izz) * (ib / p.Izz);
}

D spin_largest_xy_moment(const Properties& p) {
  const D root = sqrt((p.Ixx - p.Iyy) * (p.Ixx - p.Iyy) + 4.0 * p.Ixy * p.Ixy);
  return 0.5 * (p.Ixx + p.Iyy + root);
}

D evaluate(const GoalSpec& spec, const D* outer, const D* inner, Rows& rows) {
  D shell[10], filled[10];
  for (int j = 0; j < 10; ++j) {
    shell[j] = outer[j] - inner[j];
    filled[j] = shell[j] + spec.fill_density * inner[j];
  }
  const Properties p = properties_of(shell);
  switch (spec.kind) {
    case GoalKind::stand:
      add_support_rows(spec, p, rows);
      return stand_objective(p);
    case GoalKind::stand_filled: {
      const Properties full = properties_of(filled);
      add_support_rows(spec, p, rows);
      add_support_rows(spec, full, rows);
      return stand_objective(p) + stand_objective(full);
    }
    case GoalKind::roly_poly:
      rows.equality.push_back(p.cx - spec.axis_point.x());
      rows.equality.push_back(p.cy - spec.axis_point.y());
      rows.inequality.push_back(p.cz - (spec.axis_point.z() - spec.epsilon));
      return p.cz;
    case GoalKind::spin:
      rows.equality.push_back(p.cx - spec.axis_point.x());
      rows.equality.push_back(p.cy - spec.axis_point.y());
      rows.equality.push_back(p.Izx / p.Izz);
      rows.equality.push_back(p.Iyz / p.Izz);
      rows.inequality.push_back(spec.axis_point.z() - p.cz);
      rows.inequality.push_back((spin_largest_xy_moment(p) - p.Izz) / p.Izz);
      return p.m * p.cz + spin_ratio_term(p);
    case GoalKind::volume: {
      const D relative = (inner[kIntVolume] - spec.target_volume) / spec.target_volume;
      rows.equality.push_back(relative);
      return relative * relative;
    }
    case GoalKind::floating: {
      const D v_out = outer[kIntVolume];
      const D cbx = outer[kIntX] / v_out, cby = outer[kIntY] / v_out, cbz = outer[kIntZ] / v_out;
      const D balance = (spec.fluid_density * v_out - p.m) / v_out;
      rows.equality.push_back(balance);
      rows.equality.push_back(p.cx - cbx);
      rows.equality.push_back(p.cy - cby);
      rows.inequality.push_back(p.cz - (cbz - spec.epsilon));
      return balance * balance;
    }
  }
  return D(0.0);
}

void copy_rows(const std::vector<D>& rows, Eigen::VectorXd& values, Jacobian20& jacobian) {
  values.resize(static_cast<Eigen::Index>(rows.size()));
  jacobian.resize(static_cast<Eigen::Index>(rows.size()), 20);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    values(static_cast<Eigen::Index>(r)) = rows[r].value;
    for (int j = 0; j < 20; ++j) jacobian(static_cast<Eigen::Index>(r), j) = rows[r].grad[static_cast<std::size_t>(j)];
  }
}

}  // namespace

const char* to_string(GoalKind kind) {
  switch (kind) {
    case GoalKind::stand: return "stand";
    case GoalKind::stand_filled: return "stand-filled";
    case GoalKind::roly_poly: return "roly-poly";
    case GoalKind::spin: return "spin";
    case GoalKind::volume: return "volume";
    case GoalKind::floating: return "float";
  }
  return "?";
}

bool parse_goal_kind(const std::string& name, GoalKind& kind) {
  for (GoalKind k : {GoalKind::stand, GoalKind::stand_filled, GoalKind::roly_poly, GoalKind::spin, GoalKind::volume,
                     GoalKind::floating})
    if (name == to_string(k)) {
      kind = k;
      return true;
    }
  return false;
}

std::string check_goal_spec(const GoalSpec& spec) {
  const bool needs_polygon = spec.kind == GoalKind::stand || spec.kind == GoalKind::stand_filled;
  if (needs_polygon && spec.support_polygon.size() < 3)
    return "the support polygon has fewer than 3 corners: the object touches the ground in a point or a line and cannot stand (--pose stable rests it on a face, --flatten H cuts a flat base)";
  if (!(spec.margin >= 0.0)) return "margin must be >= 0";
  if (!(spec.fill_density > 0.0)) return "fill density must be > 0";
  if (!(spec.epsilon >= 0.0)) return "epsilon must be >= 0";
  if (spec.kind == GoalKind::volume && !(spec.target_volume > 0.0)) return "target volume must be > 0";
  if (spec.kind == GoalKind::floating && !(spec.fluid_density > 0.0 && spec.fluid_density < 1.0))
    return "fluid density must be in (0, 1): a solid of density 1 in a denser fluid floats as it is";
  if (!spec.axis_point.allFinite()) return "axis point must be finite";
  return {};
}

std::vector<std::string> goal_equality_names(const GoalSpec& spec) {
  switch (spec.kind) {
    case GoalKind::roly_poly: return {"cx - x_center", "cy - y_center"};
    case GoalKind::spin: return {"cx - x_tip", "cy - y_tip", "Izx/Izz", "Iyz/Izz"};
    case GoalKind::volume: return {"(V_void - V_target)/V_target"};
    case GoalKind::floating: return {"(rho V_out - m)/V_out", "cx - cbx", "cy - cby"};
    default: return {};
  }
}

std::vector<std::string> goal_inequality_names(const GoalSpec& spec) {
  std::vector<std::string> names;
  auto support = [&](const char* which) {
    for (std::size_t e = 0; e < spec.support_polygon.size(); ++e)
      names.push_back(std::string(which) + "margin - distance inside edge " + std::to_string(e));
    names.push_back(std::string(which) + "-cz");
  };
  switch (spec.kind) {
    case GoalKind::stand: support(""); break;
    case GoalKind::stand_filled: support("empty: "); support("filled: "); break;
    case GoalKind::roly_poly: names = {"cz - (z_center - epsilon)"}; break;
    case GoalKind::spin: names = {"z_tip - cz", "(Ib - Izz)/Izz"}; break;
    case GoalKind::volume: break;
    case GoalKind::floating: names = {"cz - (cbz - epsilon)"}; break;
  }
  return names;
}

int goal_integral_rows(const GoalSpec& spec) {
  switch (spec.kind) {
    case GoalKind::volume: return 1;
    case GoalKind::spin: return 10;
    default: return 4;  // the centre of mass and the volumes
  }
}

GoalValues evaluate_goal(const GoalSpec& spec, const Vector10d& outer, const Vector10d& inner) {
  D out[10], in[10];
  for (int j = 0; j < 10; ++j) {
    out[j] = D::variable(outer(j), j);
    in[j] = D::variable(inner(j), 10 + j);
  }
  Rows rows;
  const D f = evaluate(spec, out, in, rows);
  GoalValues values;
  values.objective = f.value;
  for (int j = 0; j < 20; ++j) values.objective_gradient(j) = f.grad[static_cast<std::size_t>(j)];
  copy_rows(rows.equality, values.equality, values.equality_jacobian);
  copy_rows(rows.inequality, values.inequality, values.inequality_jacobian);
  return values;
}

}  // namespace offsetopt
