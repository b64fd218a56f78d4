#include "geometry/bvh.h"

#include <algorithm>
#include <stdexcept>

namespace offsetopt {

std::string BvhOptions::check() const {
  if (leaf_size < 1 || leaf_size > 64) return "BvhOptions::leaf_size must be in [1, 64]";
  return std::string();
}

TriangleBvh::TriangleBvh(const Vertices& V, const Faces& F, const BvhOptions& options)
    : V_(V), F_(F), leaf_size_(options.leaf_size) {
  if (const std::string problem = options.check(); !problem.empty()) throw std::invalid_argument(problem);
  const int face_count = static_cast<int>(F_.rows());
  for (int f = 0; f < face_count; ++f)
    for (int k = 0; k < 3; ++k)
      if (F_(f, k) < 0 || F_(f, k) >= V_.rows()) throw std::invalid_argument("TriangleBvh: face index out of range");
  if (!V_.allFinite()) throw std::invalid_argument("TriangleBvh: non-finite vertex coordinate");
  Aabb all;
  for (Eigen::Index i = 0; i < V_.rows(); ++i) all.extend(Eigen::Vector3d(V_.row(i).transpose()));
  diagonal_ = all.empty() ? 0.0 : (all.hi - all.lo).norm();
  if (face_count == 0) return;
  corners_.resize(static_cast<std::size_t>(9) * static_cast<std::size_t>(face_count));
  for (int f = 0; f < face_count; ++f)
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) corners_[static_cast<std::size_t>(9 * f + 3 * k + a)] = V_(F_(f, k), a);
  face_boxes_.resize(static_cast<std::size_t>(face_count));
  for (int f = 0; f < face_count; ++f)
    for (int k = 0; k < 3; ++k) face_boxes_[static_cast<std::size_t>(f)].extend(corner(f, k));
  std::vector<int> order(static_cast<std::size_t>(face_count));
  std::vector<Eigen::Vector3d> centroids(static_cast<std::size_t>(face_count));
  for (int f = 0; f < face_count; ++f) {
    order[static_cast<std::size_t>(f)] = f;
    centroids[static_cast<std::size_t>(f)] = (corner(f, 0) + corner(f, 1) + corner(f, 2)) / 3.0;
  }
  nodes_.reserve(static_cast<std::size_t>(2 * (face_count / leaf_size_ + 1)));
  leaf_faces_.reserve(static_cast<std::size_t>(face_count));
  build(order, centroids, 0, face_count, 0);
}

int TriangleBvh::build(std::vector<int>& order, std::vector<Eigen::Vector3d>& centroids, int begin, int end, int depth) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Aabb box, centroid_box;
  for (int k = begin; k < end; ++k) {
    const int f = order[static_cast<std::size_t>(k)];
    box.extend(face_boxes_[static_cast<std::size_t>(f)]);
    centroid_box.extend(centroids[static_cast<std::size_t>(f)]);
  }
  nodes_[static_cast<std::size_t>(index)].box = box.inflated(box_margin());
  // The traversal stack holds 128 entries; a median split reaches depth log2(#F) < 40, the cap
  // only matters for pathological input and then makes a larger leaf.
  if (end - begin <= leaf_size_ || depth >= 60) {
    std::sort(order.begin() + begin, order.begin() + end);
    BvhNode& leaf = nodes_[static_cast<std::size_t>(index)];
    leaf.first = static_cast<int>(leaf_faces_.size());
    leaf.count = end - begin;
    for (int k = begin; k < end; ++k) leaf_faces_.push_back(order[static_cast<std::size_t>(k)]);
    return index;
  }
  const int axis = centroid_box.longest_axis();
  const int middle = begin + (end - begin) / 2;
  // Strict total order (coordinate, then face index): the two halves are the same sets whatever
  // the nth_element implementation does.
  std::nth_element(order.begin() + begin, order.begin() + middle, order.begin() + end, [&](int a, int b) {
    const double ca = centroids[static_cast<std::size_t>(a)][axis], cb = centroids[static_cast<std::size_t>(b)][axis];
    return ca < cb || (ca == cb && a < b);
  });
  const int left = build(order, centroids, begin, middle, depth + 1);
  const int right = build(order, centroids, middle, end, depth + 1);
  nodes_[static_cast<std::size_t>(index)].left = left;
  nodes_[static_cast<std::size_t>(index)].right = right;
  return index;
}

}  // namespace offsetopt
