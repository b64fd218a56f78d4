// The quadric correction's safeguards (optimize/quadric_correction.h) on models with closed forms:
// - rows that move twice as far as the first order says: Newton steps alone oscillate for ever at
//   the same distance, divided by the observed gain they land on the root at the second step;
// - regula falsi back along a step that crossed the root, halfway otherwise;
// - the violation counts the equalities and the violated inequalities only.
#include <doctest/doctest.h>

#include <cmath>

#include <Eigen/LU>

#include "optimize/quadric_correction.h"

using namespace offsetopt;

namespace {

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) v(i++) = x;
  return v;
}

}  // namespace

TEST_CASE("quadric correction: the observed gain turns an oscillating Newton iteration into one that lands") {
  // Two equality rows r(c) = A (c − c*) with A twice the model M the steps are taken with.
  Eigen::Matrix2d M;
  M << 1.0, 0.3, -0.2, 0.8;
  const Eigen::Matrix2d A = 2.0 * M;
  const Eigen::Vector2d target(0.4, -1.1);
  auto rows = [&](const Eigen::Vector2d& c) { return Eigen::VectorXd(A * (c - target)); };
  auto run = [&](bool with_gain) {
    Eigen::Vector2d c(1.0, 1.0);
    double gain = 1.0;
    Eigen::VectorXd before, predicted;
    double last = 0.0;
    for (int round = 0; round < 6; ++round) {
      const Eigen::VectorXd r = rows(c);
      last = goal_violation(r, 2);
      if (with_gain && predicted.size()) gain = observed_gain(before, predicted, r);
      const Eigen::Vector2d step = -M.inverse() * r / gain;
      before = r;
      predicted = r + M * step;
      c += step;
    }
    return last;
  };
  const double start = goal_violation(rows(Eigen::Vector2d(1.0, 1.0)), 2);
  CHECK(run(false) == doctest::Approx(start).epsilon(1e-9));  // −(c − c*) each round
  CHECK(run(true) < 1e-12 * start);
}

TEST_CASE("quadric correction: the gain is the least-squares ratio of the rows' move to the predicted one, clamped") {
  CHECK(observed_gain(vec({0.0, 0.0}), vec({1.0, 2.0}), vec({2.0, 4.0})) == doctest::Approx(2.0));
  CHECK(observed_gain(vec({1.0}), vec({0.0}), vec({-0.5})) == doctest::Approx(1.5));
  CHECK(observed_gain(vec({0.0}), vec({1.0}), vec({100.0})) == 5.0);
  CHECK(observed_gain(vec({0.0}), vec({1.0}), vec({-3.0})) == 0.2);
  CHECK(observed_gain(vec({1.0}), vec({1.0}), vec({3.0})) == 1.0);  // nothing predicted
}

TEST_CASE("quadric correction: stepping back aims at the root of the row furthest from met") {
  // The equality (row 0) was the worst at the best round and crossed zero: regula falsi.
  CHECK(step_back_fraction(vec({-0.16, 0.01}), vec({0.156, 0.0}), 1) == doctest::Approx(0.16 / 0.316));
  // The worst is the violated inequality (row 1), now met: its root along the segment.
  CHECK(step_back_fraction(vec({0.01, 0.3}), vec({0.02, -0.1}), 1) == doctest::Approx(0.75));
  // No change of sign: halfway; a crossing near an end is kept inside [0.1, 0.9].
  CHECK(step_back_fraction(vec({0.5, 0.0}), vec({0.7, 0.0}), 1) == 0.5);
  CHECK(step_back_fraction(vec({-1.0}), vec({0.01}), 1) == 0.9);
  CHECK(step_back_fraction(vec({-0.01}), vec({1.0}), 1) == 0.1);
}

TEST_CASE("quadric correction: met inequalities do not count as violation") {
  CHECK(goal_violation(vec({0.3, -0.4, -5.0, 0.0}), 2) == doctest::Approx(0.5));
  CHECK(goal_violation(vec({0.0, 3.0, 4.0}), 1) == doctest::Approx(5.0));
}
