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
  std::vector<BuildItem> items(static_cast<std::size_t>(face_count));
  for (int f = 0; f < face_count; ++f) {
    const Eigen::Vector3d c = (corner(f, 0) + corner(f, 1) + corner(f, 2)) / 3.0;
    items[static_cast<std::size_t>(f)] = {{c.x(), c.y(), c.z()}, f};
  }
  nodes_.reserve(static_cast<std::size_t>(2 * (face_count / leaf_size_ + 1)));
  leaf_faces_.reserve(static_cast<std::size_t>(face_count));
  Aabb bounds;
  build(items, 0, face_count, 0, bounds);
}

int TriangleBvh::build(std::vector<BuildItem>& items, int begin, int end, int depth, Aabb& bounds) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  // The traversal stack holds 128 entries; a median split reaches depth log2(#F) < 40, the cap
  // only matters for pathological input and then makes a larger leaf.
  if (end - begin <= leaf_size_ || depth >= 60) {
    std::sort(items.begin() + begin, items.begin() + end, [](const BuildItem& a, const BuildItem& b) { return a.face < b.face; });
    BvhNode& leaf = nodes_[static_cast<std::size_t>(index)];
    leaf.first = static_cast<int>(leaf_faces_.size());
    leaf.count = end - begin;
    bounds = Aabb();
    for (int k = begin; k < end; ++k) {
      const int f = items[static_cast<std::size_t>(k)].face;
      bounds.extend(face_boxes_[static_cast<std::size_t>(f)]);
      leaf_faces_.push_back(f);
    }
    leaf.box = bounds.inflated(box_margin());
    return index;
  }
  Aabb centroid_box;
  for (int k = begin; k < end; ++k) {
    const double* c = items[static_cast<std::size_t>(k)].centroid;
    centroid_box.extend(Eigen::Vector3d(c[0], c[1], c[2]));
  }
  const int axis = centroid_box.longest_axis();
  const int middle = begin + (end - begin) / 2;
  // Strict total order (coordinate, then face index): the two halves are the same sets whatever
  // the nth_element implementation does, so the tree is too.
  std::nth_element(items.begin() + begin, items.begin() + middle, items.begin() + end, [axis](const BuildItem& a, const BuildItem& b) {
    return a.centroid[axis] < b.centroid[axis] || (a.centroid[axis] == b.centroid[axis] && a.face < b.face);
  });
  // A node's box is the union of its faces' boxes, inflated: the union of its children's (min
  // and max are exact, and rounding the inflation is monotone, so it is the same box).
  Aabb left_bounds, right_bounds;
  const int left = build(items, begin, middle, depth + 1, left_bounds);
  const int right = build(items, middle, end, depth + 1, right_bounds);
  bounds = left_bounds;
  bounds.extend(right_bounds);
  BvhNode& node = nodes_[static_cast<std::size_t>(index)];
  node.box = bounds.inflated(box_margin());
  node.left = left;
  node.right = right;
  return index;
}

}  // namespace offsetopt
