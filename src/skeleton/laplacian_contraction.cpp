#include "skeleton/laplacian_contraction.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
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

// L L for the Laplacians of one mesh (their pattern never changes), bit for bit the values of
// Eigen's `L * L` with its symbolic work done once: Eigen sums entry (i, j) over the entries k of
// column j of the right factor in storage order (each column of the left factor visited in its
// own order), the first term assigned; the plan lists those (left, right) value positions in
// that order for every entry of the product.
class RepeatedSquare {
 public:
  // `square` = L * L as Eigen computed it (compressed, sorted).
  RepeatedSquare(const Eigen::SparseMatrix<double>& L, const Eigen::SparseMatrix<double>& square)
      : outer_(L.outerIndexPtr(), L.outerIndexPtr() + L.outerSize() + 1),
        inner_(L.innerIndexPtr(), L.innerIndexPtr() + L.nonZeros()) {
    valid_ = L.isCompressed() && square.isCompressed() && square.outerSize() == L.outerSize();
    struct Term {
      int row, left, right;
    };
    std::vector<Term> column;
    term_start_.assign(1, 0);
    for (Eigen::Index j = 0; valid_ && j < L.outerSize(); ++j) {
      column.clear();
      for (int right = outer_[j]; right < outer_[j + 1]; ++right) {
        const int k = inner_[right];
        for (int left = outer_[k]; left < outer_[k + 1]; ++left) column.push_back({inner_[left], left, right});
      }
      std::stable_sort(column.begin(), column.end(), [](const Term& a, const Term& b) { return a.row < b.row; });
      std::size_t t = 0;
      for (int p = square.outerIndexPtr()[j]; p < square.outerIndexPtr()[j + 1]; ++p) {
        const int row = square.innerIndexPtr()[p];
        if (t == column.size() || column[t].row != row) valid_ = false;
        for (; t < column.size() && column[t].row == row; ++t) terms_.emplace_back(column[t].left, column[t].right);
        term_start_.push_back(static_cast<int>(terms_.size()));
      }
      if (t != column.size()) valid_ = false;
    }
  }

  // Whether the plan applies to L (the pattern it was built for).
  bool matches(const Eigen::SparseMatrix<double>& L) const {
    return valid_ && L.isCompressed() && L.outerSize() + 1 == static_cast<Eigen::Index>(outer_.size()) &&
           std::equal(outer_.begin(), outer_.end(), L.outerIndexPtr()) &&
           std::equal(inner_.begin(), inner_.end(), L.innerIndexPtr());
  }

  // square's values ← those of L * L (square has the pattern of the construction).
  void evaluate(const Eigen::SparseMatrix<double>& L, Eigen::SparseMatrix<double>& square) const {
    const double* x = L.valuePtr();
    double* out = square.valuePtr();
    for (std::size_t v = 0; v + 1 < term_start_.size(); ++v) {
      int t = term_start_[v];
      double sum = x[terms_[t].first] * x[terms_[t].second];
      for (++t; t < term_start_[v + 1]; ++t) sum += x[terms_[t].first] * x[terms_[t].second];
      out[v] = sum;
    }
  }

 private:
  std::vector<int> outer_, inner_;
  std::vector<int> term_start_;  // per value of the square: its first term
  std::vector<std::pair<int, int>> terms_;
  bool valid_ = false;
};

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
  std::optional<RepeatedSquare> square;
  Eigen::SparseMatrix<double> A;
  result.status = ContractionStatus::step_cap;
  for (int step = 1; step <= options.max_steps; ++step) {
    const Eigen::SparseMatrix<double> L = cotan_laplacian(X, relabelled, cotan_options);
    // L is symmetric, so L^T L = L L. Its diagonal sum_j L_ij^2 is structurally present.
    if (square && square->matches(L)) {
      square->evaluate(L, A);
    } else {
      A = L * L;
      square.emplace(L, A);
    }
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
