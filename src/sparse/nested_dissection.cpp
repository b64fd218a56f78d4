#include "sparse/nested_dissection.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <utility>

namespace offsetopt {

std::string NestedDissectionOptions::check() const {
  if (leaf_size < 1) return "leaf_size must be at least 1";
  return {};
}

namespace {

class Dissector {
 public:
  Dissector(const Eigen::SparseMatrix<double>& pattern, const Vertices& positions, int leaf_size)
      : positions_(positions), leaf_size_(leaf_size), side_(static_cast<std::size_t>(pattern.rows()), 0) {
    build_adjacency(pattern);
  }

  std::vector<int> run(DissectionSplit* split) {
    std::vector<int> all(side_.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    order_.reserve(all.size());
    split_ = split;
    dissect(all);
    return std::move(order_);
  }

 private:
  // Symmetric adjacency without the diagonal, in CSR form (both triangles, whatever was stored).
  void build_adjacency(const Eigen::SparseMatrix<double>& pattern) {
    const int n = static_cast<int>(pattern.rows());
    std::vector<int> degree(static_cast<std::size_t>(n) + 1, 0);
    for (int col = 0; col < n; ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(pattern, col); it; ++it) {
        const int row = static_cast<int>(it.row());
        if (row == col) continue;
        ++degree[static_cast<std::size_t>(row)];
        ++degree[static_cast<std::size_t>(col)];
      }
    }
    start_.assign(static_cast<std::size_t>(n) + 1, 0);
    for (int i = 0; i < n; ++i) start_[i + 1] = start_[i] + degree[i];
    neighbours_.resize(static_cast<std::size_t>(start_[n]));
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int col = 0; col < n; ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(pattern, col); it; ++it) {
        const int row = static_cast<int>(it.row());
        if (row == col) continue;
        neighbours_[fill[row]++] = col;
        neighbours_[fill[col]++] = row;
      }
    }
    // Duplicates (both triangles stored) are harmless: they only repeat a test.
  }

  // Candidate cut normals: the leading principal axis of the subset; for the large subsets of the
  // first levels, whose separators dominate the factorisation cost, also the second axis and the
  // two diagonals between them (about 10% fewer operations than the leading axis alone, at half
  // the ordering time of trying all four everywhere).
  std::vector<Eigen::Vector3d> cut_directions(const std::vector<int>& subset) const {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int v : subset) centroid += positions_.row(v).transpose();
    centroid /= static_cast<double>(subset.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (int v : subset) {
      const Eigen::Vector3d d = positions_.row(v).transpose() - centroid;
      covariance += d * d.transpose();
    }
    // compute() is the iterative solver: no libm trigonometry (computeDirect uses acos/cos).
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    const Eigen::Vector3d major = eigen.eigenvectors().col(2);
    const Eigen::Vector3d middle = eigen.eigenvectors().col(1);
    if (subset.size() * 16 < side_.size()) return {major};
    return {major, middle, (major + middle).normalized(), (major - middle).normalized()};
  }

  struct Split {
    std::vector<int> first, second, separator;
    double score = 0.0;
  };

  // Splits at the median of positions·direction; the separator is the smaller of the two sides'
  // boundaries (vertices with a neighbour on the other side).
  Split split_along(const std::vector<int>& subset, const Eigen::Vector3d& direction) {
    keyed_.clear();
    for (int v : subset) keyed_.emplace_back(positions_.row(v).dot(direction), v);
    const std::size_t half = keyed_.size() / 2;
    std::nth_element(keyed_.begin(), keyed_.begin() + static_cast<std::ptrdiff_t>(half), keyed_.end());
    const int first_tag = ++tag_counter_, second_tag = ++tag_counter_;
    for (std::size_t i = 0; i < keyed_.size(); ++i) side_[keyed_[i].second] = i < half ? first_tag : second_tag;

    Split split;
    std::vector<int> first_boundary, second_boundary;
    for (std::size_t i = 0; i < keyed_.size(); ++i) {
      const int v = keyed_[i].second;
      const int other = i < half ? second_tag : first_tag;
      bool on_boundary = false;
      for (int p = start_[v]; p < start_[v + 1]; ++p) {
        if (side_[neighbours_[p]] == other) {
          on_boundary = true;
          break;
        }
      }
      std::vector<int>& interior = i < half ? split.first : split.second;
      std::vector<int>& boundary = i < half ? first_boundary : second_boundary;
      (on_boundary ? boundary : interior).push_back(v);
    }
    if (second_boundary.size() < first_boundary.size()) {
      split.first.insert(split.first.end(), first_boundary.begin(), first_boundary.end());
      split.separator = std::move(second_boundary);
    } else {
      split.second.insert(split.second.end(), second_boundary.begin(), second_boundary.end());
      split.separator = std::move(first_boundary);
    }
    const double imbalance =
        std::abs(static_cast<double>(split.first.size()) - static_cast<double>(split.second.size())) /
        static_cast<double>(subset.size());
    split.score = static_cast<double>(split.separator.size()) * (1.0 + imbalance);
    return split;
  }

  void dissect(std::vector<int>& subset) {
    if (static_cast<int>(subset.size()) <= leaf_size_) {
      // Canonical order inside a leaf, so the result does not depend on nth_element's arrangement.
      std::sort(subset.begin(), subset.end());
      order_.insert(order_.end(), subset.begin(), subset.end());
      return;
    }
    Split best;
    bool have_best = false;
    for (const Eigen::Vector3d& direction : cut_directions(subset)) {
      Split candidate = split_along(subset, direction);
      if (!have_best || candidate.score < best.score) {
        best = std::move(candidate);
        have_best = true;
      }
    }
    subset.clear();
    subset.shrink_to_fit();
    if (best.first.empty() || best.second.empty()) {
      // Nothing to gain (e.g. all vertices coincide): order the rest as one block.
      std::vector<int> rest = std::move(best.first);
      rest.insert(rest.end(), best.second.begin(), best.second.end());
      rest.insert(rest.end(), best.separator.begin(), best.separator.end());
      std::sort(rest.begin(), rest.end());
      order_.insert(order_.end(), rest.begin(), rest.end());
      return;
    }
    for (int v : best.separator) side_[v] = -1;  // a separator vertex belongs to no later subset
    if (split_) {  // the top level: record the sizes of its three parts, once
      *split_ = {static_cast<int>(best.first.size()), static_cast<int>(best.second.size()),
                 static_cast<int>(best.separator.size())};
      split_ = nullptr;
    }
    dissect(best.first);
    dissect(best.second);
    std::sort(best.separator.begin(), best.separator.end());
    order_.insert(order_.end(), best.separator.begin(), best.separator.end());
  }

  const Vertices& positions_;
  int leaf_size_;
  std::vector<int> side_;
  int tag_counter_ = 0;
  std::vector<int> start_, neighbours_;
  std::vector<std::pair<double, int>> keyed_;
  std::vector<int> order_;
  DissectionSplit* split_ = nullptr;
};

}  // namespace

std::vector<int> nested_dissection(const Eigen::SparseMatrix<double>& pattern, const Vertices& positions,
                                   const NestedDissectionOptions& options, DissectionSplit* split) {
  if (split) *split = {};
  Dissector dissector(pattern, positions, options.leaf_size);
  return dissector.run(split);
}

}  // namespace offsetopt
