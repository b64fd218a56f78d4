// The six goals of the optimiser (Musialski et al. 2015, section 6.2; docs/design.md "Goals") as
// closed-form functions of the raw volume integrals of the outer and the inner surface:
//   shell = outer − inner (the printed material, density 1), filled = shell + ρ_fill · inner.
// Each goal gives an objective f, equality constraints h = 0 and inequality constraints c ≤ 0,
// with exact derivatives with respect to the 20 numbers [outer integrals; inner integrals]
// (forward-mode dual numbers, util/dual.h). The optimiser chains them with ∂integrals/∂α.
//
// All positions (support polygon, axis points) are in the frame the integrals are measured in:
// the optimiser's normalised frame (ground contact centroid at the origin, z up, bounding-box
// diagonal 1), so every value below is O(1) and tolerances are relative to the model's size.
//
//   stand         f = cx² + cy² + cz (eq. 5);  for every support-polygon edge e (inward unit
//                 normal n_e, offset d_e): margin − (n_e·c_xy − d_e) ≤ 0  (the exact polygon shrunk
//                 by the margin, not the paper's inscribed circle); −cz ≤ 0.
//   stand-filled  f = f_stand(empty) + f_stand(filled) (eq. 6), the edge constraints for both.
//   roly-poly     f = cz (eq. 7);  cx − x0 = 0, cy − y0 = 0 (x0, y0: the sphere's centre);
//                 cz − (z0 − ε) ≤ 0 (z0: the sphere centre's height).
//   spin          f = m·cz + (Ia/Izz)² + (Ib/Izz)² (eq. 8, Bächer et al. 2014; Ia ≤ Ib the
//                 eigenvalues of the xy block);  cx − x0 = 0, cy − y0 = 0 (the tip), Izx = 0,
//                 Iyz = 0 (divided by Izz);  −(cz − z0) ≤ 0;  Ib − Izz ≤ 0 (z is the axis of the
//                 largest moment: a stable spin).
//   volume        f = ((V_void − V_t)/V_t)²;  (V_void − V_t)/V_t = 0.
//   float         f = ((ρ−1)V_out + V_in)² / V_out² (eq. 9: fully submerged balance);
//                 (ρ V_out − m)/V_out = 0;  cx − cbx = 0, cy − cby = 0 (c_b: centroid of the
//                 outer surface, the centre of buoyancy);  cz − (cbz − ε) ≤ 0.
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mass/volume_integrals.h"

namespace offsetopt {

enum class GoalKind { stand, stand_filled, roly_poly, spin, volume, floating };

// "stand", "stand-filled", "roly-poly", "spin", "volume", "float".
const char* to_string(GoalKind kind);
// Parses the names above; false when the name is unknown.
bool parse_goal_kind(const std::string& name, GoalKind& kind);

struct GoalSpec {
  GoalKind kind = GoalKind::stand;
  std::vector<Eigen::Vector2d> support_polygon;  // stand, stand-filled: CCW convex, >= 3 points
  double margin = 0.0;                           // stand, stand-filled: >= 0
  double fill_density = 1.0;                     // stand-filled: > 0
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();  // roly-poly: sphere centre; spin: tip
  double epsilon = 0.0;                          // roly-poly, float: safeguard >= 0
  double target_volume = 0.0;                    // volume: > 0
  double fluid_density = 1.0;                    // float: in (0, 1)
};

// Empty string when valid, else what is wrong.
std::string check_goal_spec(const GoalSpec& spec);

using Vector20d = Eigen::Matrix<double, 20, 1>;
using Jacobian20 = Eigen::Matrix<double, Eigen::Dynamic, 20, Eigen::RowMajor>;

struct GoalValues {
  double objective = 0.0;
  Vector20d objective_gradient = Vector20d::Zero();  // ∂f/∂[outer; inner]
  Eigen::VectorXd equality;                          // h, = 0 when met
  Jacobian20 equality_jacobian;
  Eigen::VectorXd inequality;                        // c, <= 0 when met
  Jacobian20 inequality_jacobian;
};

// Names of the constraint rows, in order (for reports), and their counts for a spec.
std::vector<std::string> goal_equality_names(const GoalSpec& spec);
std::vector<std::string> goal_inequality_names(const GoalSpec& spec);

// How many leading integrals (kInt order) the goal's values depend on: 1 (the volume), 4 (and
// the first moments) or 10 (and the second moments). evaluate_goal's derivatives by the other
// integrals, outer and inner, are exactly 0, so the optimiser needs no Jacobian rows for them, and
// its values and derivatives do not depend on those integrals at all (they may be NaN): the
// optimiser's inner evaluations do not sum them.
int goal_integral_rows(const GoalSpec& spec);

// `outer` and `inner` are raw integrals measured from the same origin; `inner` may be all zero
// (no void). The shell's volume must be positive.
GoalValues evaluate_goal(const GoalSpec& spec, const Vector10d& outer, const Vector10d& inner);

}  // namespace offsetopt
