#include "skeleton/laplacian_contraction.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "geometry/cotan_laplacian.h"
#include "sparse/fill_reducing_ordering.h"
#include "sparse/supernodal_cholesky.h"

namespace offsetopt {

namespace {

struct Measures {
  Eigen::VectorXd one_ring_area;  // #V
  double area = 0.0;
  double volume = 0.0;
};

// Face areas summed per vertex, total area and signed enclosed volume (divergence theorem), in
// face order (a fixed summation order, so results are reproducible).
Measures measure(const Vertices& X, const Faces& F) {
  Measures m;
  m.one_ring_area = Eigen::VectorXd::Zero(X.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = X.row(F(f, 0)), b = X.row(F(f, 1)), c = X.row(F(f, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    m.area += area;
    m.volume += a.dot(b.cross(c)) / 6.0;
    for (int k = 0; k < 3; ++k) m.one_ring_area[F(f, k)] += area;
  }
  return m;
}

// square's values ← those of L L, for a `square` that already holds the product's pattern (an
// earlier L L of the same mesh: the pattern never changes). Bit for bit the values of Eigen's
// `L * L`, whose symbolic work and two sorting transposes it saves: for each column j, entry
// (i, j) gets its terms over the entries k of column j of the right factor in storage order
// (column k of the left factor visited in its own order), the first term assigned. Returns false,
// leaving `square` in an unspecified state, when the patterns disagree.
bool square_into(const Eigen::SparseMatrix<double>& L, Eigen::SparseMatrix<double>& square,
                 std::vector<double>& sums, std::vector<char>& touched) {
  const Eigen::Index n = L.outerSize();
  if (!L.isCompressed() || !square.isCompressed() || square.outerSize() != n || square.innerSize() != n) return false;
  sums.resize(static_cast<std::size_t>(n));
  touched.assign(static_cast<std::size_t>(n), 0);
  const int* outer = L.outerIndexPtr();
  const int* inner = L.innerIndexPtr();
  const double* value = L.valuePtr();
  for (Eigen::Index j = 0; j < n; ++j) {
    int count = 0;
    for (int right = outer[j]; right < outer[j + 1]; ++right) {
      const double y = value[right];
      const int k = inner[right];
      for (int left = outer[k]; left < outer[k + 1]; ++left) {
        const std::size_t i = static_cast<std::size_t>(inner[left]);
        if (!touched[i]) {
          touched[i] = 1;
          sums[i] = value[left] * y;
          ++count;
        } else {
          sums[i] += value[left] * y;
        }
      }
    }
    const int begin = square.outerIndexPtr()[j], end = square.outerIndexPtr()[j + 1];
    if (end - begin != count) return false;
    for (int p = begin; p < end; ++p) {
      const std::size_t i = static_cast<std::size_t>(square.innerIndexPtr()[p]);
      if (!touched[i]) return false;
      touched[i] = 0;
      square.valuePtr()[p] = sums[i];
    }
  }
  return true;
}

// Contracts the decimated copy and carries its positions back to every input vertex.
ContractionResult coarse_to_fine(const Vertices& V, const Faces& F, const ContractionOptions& options) {
  const CoarseCopy copy = coarse_copy(V, F, options.coarse_vertices, options.threads);
  ContractionResult result = laplacian_contraction_of_copy(copy, options);
  if (result.status == ContractionStatus::degenerate_input) result.V = V;
  return result;
}

}  // namespace

std::string ContractionOptions::check() const {
  if (!(std::isfinite(initial_laplacian_weight) && initial_laplacian_weight > 0.0))
    return "ContractionOptions::initial_laplacian_weight must be finite and > 0";
  if (!(std::isfinite(initial_laplacian_weight_per_area) && initial_laplacian_weight_per_area >= 0.0))
    return "ContractionOptions::initial_laplacian_weight_per_area must be finite and >= 0";
  if (!(std::isfinite(laplacian_weight_growth) && laplacian_weight_growth >= 1.0 && laplacian_weight_growth <= 100.0))
    return "ContractionOptions::laplacian_weight_growth must be in [1, 100]";
  if (!(std::isfinite(attraction_weight) && attraction_weight > 0.0))
    return "ContractionOptions::attraction_weight must be finite and > 0";
  if (!(stop_volume_ratio >= 0.0 && stop_volume_ratio < 1.0))
    return "ContractionOptions::stop_volume_ratio must be in [0, 1)";
  if (!(max_steps >= 1 && max_steps <= 100)) return "ContractionOptions::max_steps must be in [1, 100]";
  if (!(cotan_sine_floor > 0.0 && cotan_sine_floor < 1.0))
    return "ContractionOptions::cotan_sine_floor must be in (0, 1)";
  if (!(mollify_margin >= 0.0 && mollify_margin <= 0.1))
    return "ContractionOptions::mollify_margin must be in [0, 0.1]";
  if (!(area_ratio_floor > 0.0 && area_ratio_floor < 1.0))
    return "ContractionOptions::area_ratio_floor must be in (0, 1)";
  if (!(threads >= 1 && threads <= 256)) return "ContractionOptions::threads must be in [1, 256]";
  if (!(coarse_above >= 0)) return "ContractionOptions::coarse_above must be >= 0";
  if (coarse_above > 0 && !(coarse_vertices >= 100 && coarse_vertices <= coarse_above))
    return "ContractionOptions::coarse_vertices must be in [100, coarse_above]";
  return std::string();
}

const char* to_string(ContractionStatus status) {
  switch (status) {
    case ContractionStatus::volume_ratio_reached: return "volume_ratio_reached";
    case ContractionStatus::step_cap: return "step_cap";
    case ContractionStatus::factorization_failed: return "factorization_failed";
    case ContractionStatus::degenerate_input: return "degenerate_input";
  }
  return "unknown";
}

ContractionResult laplacian_contraction(const Vertices& V, const Faces& F, const ContractionOptions& options) {
  if (const std::string problem = options.check(); !problem.empty()) throw std::invalid_argument(problem);
  ContractionResult result;
  result.V = V;
  result.status = ContractionStatus::degenerate_input;
  const Eigen::Index n = V.rows();
  if (n == 0 || F.rows() == 0 || !V.allFinite()) return result;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= n) throw std::invalid_argument("laplacian_contraction: face index out of range");
  if (options.coarse_above > 0 && n > options.coarse_above) return coarse_to_fine(V, F, options);
  result.contracted_vertices = n;

  const Eigen::RowVector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  const double diagonal = (hi - lo).norm();
  if (!(diagonal > 0.0)) return result;
  const Eigen::RowVector3d center = 0.5 * (lo + hi);
  const double scale = 1.0 / diagonal;
  const Vertices normalised = (V.rowwise() - center) * scale;

  // Relabel the vertices once by a fill-reducing ordering of the normal equations' pattern, so
  // every step assembles its matrix directly in factorisation order.
  CotanOptions cotan_options;
  cotan_options.sine_floor = options.cotan_sine_floor;
  cotan_options.mollify_margin = options.mollify_margin;
  std::vector<int> new_to_old;
  {
    const Eigen::SparseMatrix<double> L0 = cotan_laplacian(normalised, F, cotan_options);
    const Eigen::SparseMatrix<double> pattern = L0 * L0;
    FillReducingOrdering ordering = fill_reducing_ordering(pattern, normalised, L0, 2, options.threads > 1);
    new_to_old = std::move(ordering.new_to_old);
    result.ordering = ordering.method;
    result.predicted_factor_flops = ordering.counts.flops;
    result.predicted_factor_nonzeros = ordering.counts.nonzeros;
  }
  std::vector<int> old_to_new(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) old_to_new[static_cast<std::size_t>(new_to_old[static_cast<std::size_t>(k)])] = static_cast<int>(k);
  Vertices X(n, 3);
  for (Eigen::Index k = 0; k < n; ++k) X.row(k) = normalised.row(new_to_old[static_cast<std::size_t>(k)]);
  Faces relabelled(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) relabelled(f, c) = old_to_new[static_cast<std::size_t>(F(f, c))];

  const Measures initial = measure(X, relabelled);
  if (!(initial.area > 0.0)) return result;
  const Eigen::VectorXd initial_ring = initial.one_ring_area;

  const double mean_face_area = initial.area / static_cast<double>(F.rows());
  double laplacian_weight = std::max(options.initial_laplacian_weight / std::sqrt(mean_face_area),
                                     options.initial_laplacian_weight_per_area / mean_face_area);
  Eigen::VectorXd attraction = Eigen::VectorXd::Constant(n, options.attraction_weight);

  SupernodalCholesky solver;
  solver.set_thread_count(options.threads);
  bool analysed = false;
  Eigen::SparseMatrix<double> A;
  std::vector<double> square_sums;
  std::vector<char> square_touched;
  result.status = ContractionStatus::step_cap;
  for (int step = 1; step <= options.max_steps; ++step) {
    const Eigen::SparseMatrix<double> L = cotan_laplacian(X, relabelled, cotan_options);
    // L is symmetric, so L^T L = L L. Its diagonal sum_j L_ij^2 is structurally present.
    if (step == 1 || !square_into(L, A, square_sums, square_touched)) A = L * L;
    A *= laplacian_weight * laplacian_weight;
    const Eigen::VectorXd attraction_squared = attraction.array().square();
    A.diagonal() += attraction_squared;
    if (!analysed) {
      solver.analyze(A);
      analysed = true;
    }
    if (!solver.factorize(A)) {
      result.status = ContractionStatus::factorization_failed;
      break;
    }
    Eigen::MatrixXd solution = attraction_squared.asDiagonal() * Eigen::MatrixXd(X);
    solver.solve_in_place(solution);
    if (!solution.allFinite()) {
      result.status = ContractionStatus::factorization_failed;
      break;
    }
    X = solution;
    const Measures now = measure(X, relabelled);
    ContractionStep record;
    record.laplacian_weight = laplacian_weight;
    record.area_ratio = now.area / initial.area;
    record.volume_ratio = initial.volume != 0.0 ? now.volume / initial.volume : 1.0;
    result.history.push_back(record);
    result.steps = step;
    result.area_ratio = record.area_ratio;
    result.volume_ratio = record.volume_ratio;

    for (Eigen::Index i = 0; i < n; ++i) {
      const double floor = options.area_ratio_floor * initial_ring[i];
      const double ring = now.one_ring_area[i] > floor ? now.one_ring_area[i] : floor;
      attraction[i] = initial_ring[i] > 0.0 ? options.attraction_weight * std::sqrt(initial_ring[i] / ring) : options.attraction_weight;
    }
    laplacian_weight *= options.laplacian_weight_growth;
    // The rule fires after 2 to 4 steps on every mesh tried: 4 is the estimate of the whole.
    if (options.on_progress) options.on_progress(std::min(0.95, step / 4.0));
    if (options.stop_volume_ratio > 0.0 && record.volume_ratio <= options.stop_volume_ratio) {
      result.status = ContractionStatus::volume_ratio_reached;
      break;
    }
  }
  for (Eigen::Index k = 0; k < n; ++k) result.V.row(new_to_old[static_cast<std::size_t>(k)]) = X.row(k) / scale + center;
  return result;
}

ContractionResult laplacian_contraction_of_copy(const CoarseCopy& copy, const ContractionOptions& options) {
  ContractionOptions on_copy = options;
  on_copy.coarse_above = 0;
  ContractionResult result = laplacian_contraction(copy.decimated.mesh.V, copy.decimated.mesh.F, on_copy);
  result.V = carry_to_input(copy, result.V);
  return result;
}

}  // namespace offsetopt
