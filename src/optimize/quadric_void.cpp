#include "optimize/quadric_void.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "mass/volume_integrals.h"
#include "optimize/quadric_correction.h"
#include "util/neumaier_sum.h"
#include "util/parallel.h"

namespace offsetopt {

namespace {

constexpr int kDegree[10] = {0, 1, 1, 1, 2, 2, 2, 2, 2, 2};

double power(double x, int n) {
  double p = 1.0;
  for (int i = 0; i < n; ++i) p *= x;
  return p;
}

Vector10d monomials(const Eigen::Vector3d& x) {
  Vector10d m;
  m << 1.0, x.x(), x.y(), x.z(), x.x() * x.x(), x.y() * x.y(), x.z() * x.z(), x.x() * x.y(), x.y() * x.z(), x.z() * x.x();
  return m;
}

Eigen::Vector3d gradient(const Vector10d& c, const Eigen::Vector3d& x) {
  return Eigen::Vector3d(c(1) + 2.0 * c(4) * x.x() + c(7) * x.y() + c(9) * x.z(),
                         c(2) + 2.0 * c(5) * x.y() + c(7) * x.x() + c(8) * x.z(),
                         c(3) + 2.0 * c(6) * x.z() + c(8) * x.y() + c(9) * x.x());
}

// Raw integrals about the frame's origin in input units, read in the normalised frame (volume s³,
// first moments s⁴, second s⁵).
Vector10d integrals_in_frame(const Vector10d& integrals, double s) {
  Vector10d out;
  for (int k = 0; k < 10; ++k) out(k) = integrals(k) * power(s, 3 + kDegree[k]);
  return out;
}

// A frame quadric (coefficients on m(s (p − o))) in input units about o, and back.
Quadric to_input_units(const Vector10d& frame, double s, const Eigen::Vector3d& origin) {
  Quadric q;
  q.origin = origin;
  for (int k = 0; k < 10; ++k) q.coefficients(k) = frame(k) * power(s, kDegree[k]);
  return q;
}

Vector10d to_frame(const Quadric& q, double s, const Eigen::Vector3d& origin) {
  // About the frame's origin first (Quadric{−o, a}.about_zero() is a(p + o) on m(p)).
  const Vector10d c = q.origin == origin ? q.coefficients : Quadric{-origin, q.about_zero()}.about_zero();
  Vector10d out;
  for (int k = 0; k < 10; ++k) out(k) = c(k) / power(s, kDegree[k]);
  return out;
}

// The mean |∇q| over the cavity's faces on the quadric, 0 when none is.
double boundary_gradient(const Mesh& cavity, const Vector10d& c, double s, const Eigen::Vector3d& origin, double near) {
  NeumaierSum sum;
  int count = 0;
  for (Eigen::Index f = 0; f < cavity.F.rows(); ++f) {
    const Eigen::Vector3d x =
        s * ((cavity.V.row(cavity.F(f, 0)) + cavity.V.row(cavity.F(f, 1)) + cavity.V.row(cavity.F(f, 2))).transpose() / 3.0 - origin);
    const double g = gradient(c, x).norm();
    if (!(g > 0.0) || std::fabs(c.dot(monomials(x))) > near * g) continue;
    sum.add(g);
    ++count;
  }
  return count ? sum.value() / count : 0.0;
}

// ∂I/∂c (frame units) over the cavity's faces that lie on the quadric (within a tenth of a cell):
// the rest of the boundary keeps the wall and does not move with q.
Eigen::Matrix<double, 10, 10> boundary_jacobian(const Mesh& cavity, const Vector10d& c, double s, const Eigen::Vector3d& origin,
                                                double near) {
  Eigen::Matrix<double, 10, 10> J = Eigen::Matrix<double, 10, 10>::Zero();
  for (Eigen::Index f = 0; f < cavity.F.rows(); ++f) {
    const Eigen::Vector3d a = cavity.V.row(cavity.F(f, 0)).transpose(), b = cavity.V.row(cavity.F(f, 1)).transpose(),
                          d = cavity.V.row(cavity.F(f, 2)).transpose();
    const Eigen::Vector3d x = s * ((a + b + d) / 3.0 - origin);
    const Vector10d m = monomials(x);
    const double g = gradient(c, x).norm();
    if (!(g > 0.0) || std::fabs(c.dot(m)) > near * g) continue;
    const double area = 0.5 * s * s * (b - a).cross(d - a).norm();
    J -= (area / g) * (m * m.transpose());
  }
  return J;
}

// The least-norm δc that zeroes the violated rows to first order, or nothing when they cannot move.
std::optional<Vector10d> newton_step(const GoalValues& values, const Eigen::Matrix<double, 10, 10>& J) {
  std::vector<Eigen::Matrix<double, 1, 10>> rows;
  std::vector<double> rhs;
  for (Eigen::Index r = 0; r < values.equality.size(); ++r) {
    rows.push_back(values.equality_jacobian.row(r).tail<10>() * J);
    rhs.push_back(-values.equality(r));
  }
  for (Eigen::Index r = 0; r < values.inequality.size(); ++r)
    if (values.inequality(r) > 0.0) {
      rows.push_back(values.inequality_jacobian.row(r).tail<10>() * J);
      rhs.push_back(-values.inequality(r));
    }
  if (rows.empty()) return std::nullopt;
  Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), 10);
  Eigen::VectorXd b(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    A.row(static_cast<Eigen::Index>(r)) = rows[r];
    b(static_cast<Eigen::Index>(r)) = rhs[r];
  }
  // A Aᵀ y = b, δc = Aᵀ y, with a relative ridge for rows that the boundary cannot move.
  Eigen::MatrixXd G = A * A.transpose();
  const double ridge = 1e-12 * std::max(G.diagonal().maxCoeff(), 1e-300);
  G.diagonal().array() += ridge;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(G);
  if (ldlt.info() != Eigen::Success) return std::nullopt;
  const Vector10d step = A.transpose() * ldlt.solve(b);
  if (!step.allFinite()) return std::nullopt;
  return step;
}

// The programme's void is {q < 0} on its cells but for a few fractional ones, unless q ties on many
// cells: a float goal's optimum is a plane, a whole layer of cells lies on it, and the programme
// fills part of that layer where the contour of q = 0 cuts it through the centres (the buoy's first
// contour held 38,294 of void against the programme's 37,169; the float check allows 1e-3 of the
// mass, 154, so a second contour was needed). The constant δ added to q (input units) that makes
// the void of q + δ, read on the cells with each cell cut as a slab of its width along ∇q, hold
// the occupancy's volume; 0 when none within about a cell's width does.
double volume_matching_shift(const Reachability& programme, const Vector10d& q) {
  if (!programme.cells) return 0.0;
  const CarvableCells& cells = *programme.cells;
  const std::vector<std::int64_t>& list = programme.occupancy.size() == cells.mid.size() ? cells.mid : cells.inner;
  if (list.size() != programme.occupancy.size() || list.empty()) return 0.0;
  const double h = cells.grid.spacing, v = h * h * h;
  // Per cell: q at the centre and the span of q over the cell's slab, h |∇q|₁.
  std::vector<double> value(list.size()), span(list.size());
  NeumaierSum occupied;
  double widest = 0.0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Eigen::Vector3d x = cells.centre(list[i]);
    value[i] = q.dot(monomials(x));
    span[i] = h * gradient(q, x).cwiseAbs().sum();
    occupied.add(v * programme.occupancy[i]);
    if (std::fabs(value[i]) <= span[i]) widest = std::max(widest, span[i]);
  }
  if (!(widest > 0.0)) return 0.0;
  const double target = occupied.value();
  // Cells whole or empty for every shift tried are counted once; the bisection reads the rest.
  double whole = 0.0;
  std::vector<std::pair<double, double>> open;  // (value, span)
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (value[i] + widest <= -0.5 * span[i]) whole += v;
    else if (value[i] - widest < 0.5 * span[i]) open.emplace_back(value[i], span[i]);
  }
  auto volume = [&](double delta) {
    NeumaierSum sum;
    sum.add(whole);
    for (const auto& [at, width] : open)
      if (width > 0.0) sum.add(v * std::min(1.0, std::max(0.0, 0.5 - (at + delta) / width)));
      else if (at + delta < 0.0) sum.add(v);
    return sum.value();
  };
  double lo = -widest, hi = widest;  // volume(lo) >= target >= volume(hi) when a root is near
  if (volume(lo) < target || volume(hi) > target) return 0.0;
  for (int step = 0; step < 50; ++step) {
    const double mid = 0.5 * (lo + hi);
    (volume(mid) >= target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void record_round(const ContourCavity& contoured, const Vector10d& predicted, const Vector10d& written, double s,
                  const Verification& verification, bool will_correct, QuadricVoid& out) {
  ContourRound& entry = out.rounds.emplace_back(contour_round(contoured, verification, !will_correct));
  entry.delta_in_frame = written - predicted;
  entry.void_volume_offset = predicted(kIntVolume) / (s * s * s);
  entry.void_volume_contour = written(kIntVolume) / (s * s * s);
}

}  // namespace

QuadricVoid write_quadric_void(const QuadricVoidInput& input) {
  QuadricVoid out;
  const double s = 1.0 / input.diagonal;
  GoalSpec aim = input.goal_in_frame;
  aim.margin *= 1.0 + input.headroom;
  aim.epsilon *= 1.0 + input.headroom;
  const Vector10d outer = integrals_in_frame(volume_integrals(*input.outer, input.origin).values, s);
  Quadric start = input.start;
  if (input.programme) start.coefficients(0) += volume_matching_shift(*input.programme, start.about_zero());
  Vector10d c = to_frame(start, s, input.origin);
  Vector10d predicted = Vector10d::Zero();
  std::shared_ptr<ContourReuse> reuse;  // what the rounds' contours share (the outer surface's part)
  // The round closest to meeting the goal so far: its quadric (scaled as its step was taken), rows,
  // violation and integrals.
  struct Best {
    Vector10d c = Vector10d::Zero(), written = Vector10d::Zero();
    Eigen::VectorXd rows;
    double violation = std::numeric_limits<double>::infinity();
  } best;
  // The last Newton step's rows before it and as its first order predicted them, for the gain
  // (optimize/quadric_correction.h) the next step is divided by.
  struct LastStep {
    Eigen::VectorXd before, predicted;
  };
  std::optional<LastStep> last_step;
  double gain = 1.0;
  for (int round = 0; round <= input.max_rounds; ++round) {
    out.quadric = to_input_units(c, s, input.origin);
    const ContourCavity contoured =
        contour_cavity(*input.outer, *input.outer_bvh, out.quadric.about_zero(), input.contour, &reuse);
    if (!contoured.ok) {
      out.message = "the quadric void could not be contoured: " + contoured.message;
      break;
    }
    // The contour's integrals beside the goal's check, which sums them again from another origin:
    // one sum in face order each, so the same bits on any number of threads.
    std::future<Vector10d> written_integrals = start_task(input.verify.threads > 1, [&contoured, &input, s] {
      return integrals_in_frame(volume_integrals(contoured.cavity, input.origin).values, s);
    });
    VerifyInput verify = input.verify;
    verify.inner = &contoured.cavity;
    verify.goal_only = true;
    out.verification = verify_offsets(verify);
    const Vector10d written = written_integrals.get();
    const bool last = round == input.max_rounds;
    std::optional<Vector10d> step;
    Eigen::Matrix<double, 10, 10> J = Eigen::Matrix<double, 10, 10>::Zero();
    if (!out.verification.goal_met && !last) {
      // q scaled so that |∇q| is 1 on average on its boundary: the step's norm then weighs the
      // ten coefficients alike, whatever scale the programme's duals gave q.
      const double near = 0.1 * contoured.grid.spacing * s;
      const double g = boundary_gradient(contoured.cavity, c, s, input.origin, near);
      if (g > 0.0) {
        c /= g;
        const GoalValues values = evaluate_goal(aim, outer, written);
        const Eigen::VectorXd rows = goal_rows(values);
        const Eigen::Index equalities = values.equality.size();
        const double now = goal_violation(rows, equalities);
        if (last_step) gain = observed_gain(last_step->before, last_step->predicted, rows);
        last_step.reset();
        if (now > 0.5 * best.violation) {
          const double t = step_back_fraction(best.rows, rows, equalities);
          step = best.c + t * (c - best.c) - c;
          predicted = best.written + t * (written - best.written);
        } else {
          J = boundary_jacobian(contoured.cavity, c, s, input.origin, near);
          step = newton_step(values, J);
          if (step) {
            *step /= gain;
            last_step = LastStep{rows, rows + goal_row_jacobian(values) * (J * *step)};
          }
        }
        if (now < best.violation) best = Best{c, written, rows, now};
      }
      if (!step) out.message = "the quadric's boundary cannot move the goal's rows (round " + std::to_string(round) + ")";
    }
    const bool will_correct = step.has_value();
    if (!will_correct) {
      // As written: rounded to the file's precision, then verified, the faces' wall included.
      VerifiedCavity written_file =
          verify_written_cavity(verify, *input.outer, contoured.cavity, contoured.faces_below_wall, input.verify.precision);
      out.verification = std::move(written_file.verification);
      out.outer = std::move(written_file.rounded.outer);
      out.written = std::move(written_file.rounded.inner);
    }
    record_round(contoured, round == 0 ? written : predicted, written, s, out.verification, will_correct, out);
    if (!will_correct) break;
    if (!J.isZero()) predicted = written + J * *step;  // the next round's integrals to first order
    c += *step;
  }
  return out;
}

}  // namespace offsetopt
