#include "geometry/bvh.h"

#include <algorithm>
#include <stdexcept>

#include "util/parallel.h"

namespace offsetopt {

std::string BvhOptions::check() const {
  if (leaf_size < 1 || leaf_size > 64) return "BvhOptions::leaf_size must be in [1, 64]";
  if (threads < 1) return "BvhOptions::threads must be at least 1";
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
  if (options.threads < 2 || face_count < kBvhSplitBuildFaces) {
    build(items, 0, face_count, 0, bounds, nodes_, leaf_faces_);
    return;
  }
  // The root here, its subtrees on two threads, the right one into vectors of its own that are
  // then appended, its indices shifted: the nodes and leaves in the one-thread build's order.
  nodes_.emplace_back();
  split_at_median(items, 0, face_count);
  const int middle = face_count / 2;
  std::vector<BvhNode> right_nodes;
  std::vector<int> right_leaves;
  Aabb left_bounds, right_bounds;
  WorkerPool pool(2);
  pool.run_parts(2, [&](int part) {
    if (part == 0) build(items, 0, middle, 1, left_bounds, nodes_, leaf_faces_);
    else build(items, middle, face_count, 1, right_bounds, right_nodes, right_leaves);
  });
  const int node_shift = static_cast<int>(nodes_.size()), leaf_shift = static_cast<int>(leaf_faces_.size());
  for (BvhNode node : right_nodes) {
    if (node.is_leaf()) {
      node.first += leaf_shift;
    } else {
      node.left += node_shift;
      node.right += node_shift;
    }
    nodes_.push_back(node);
  }
  leaf_faces_.insert(leaf_faces_.end(), right_leaves.begin(), right_leaves.end());
  bounds = left_bounds;
  bounds.extend(right_bounds);
  BvhNode& root = nodes_.front();
  root.box = bounds.inflated(box_margin());
  root.left = 1;
  root.right = node_shift;
}

void TriangleBvh::split_at_median(std::vector<BuildItem>& items, int begin, int end) {
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
}

int TriangleBvh::build(std::vector<BuildItem>& items, int begin, int end, int depth, Aabb& bounds, std::vector<BvhNode>& nodes,
                       std::vector<int>& leaves) const {
  const int index = static_cast<int>(nodes.size());
  nodes.emplace_back();
  // The traversal stack holds 128 entries; a median split reaches depth log2(#F) < 40, the cap
  // only matters for pathological input and then makes a larger leaf.
  if (end - begin <= leaf_size_ || depth >= 60) {
    std::sort(items.begin() + begin, items.begin() + end, [](const BuildItem& a, const BuildItem& b) { return a.face < b.face; });
    BvhNode& leaf = nodes[static_cast<std::size_t>(index)];
    leaf.first = static_cast<int>(leaves.size());
    leaf.count = end - begin;
    bounds = Aabb();
    for (int k = begin; k < end; ++k) {
      const int f = items[static_cast<std::size_t>(k)].face;
      bounds.extend(face_boxes_[static_cast<std::size_t>(f)]);
      leaves.push_back(f);
    }
    leaf.box = bounds.inflated(box_margin());
    return index;
  }
  split_at_median(items, begin, end);
  const int middle = begin + (end - begin) / 2;
  // A node's box is the union of its faces' boxes, inflated: the union of its children's (min
  // and max are exact, and rounding the inflation is monotone, so it is the same box).
  Aabb left_bounds, right_bounds;
  const int left = build(items, begin, middle, depth + 1, left_bounds, nodes, leaves);
  const int right = build(items, middle, end, depth + 1, right_bounds, nodes, leaves);
  bounds = left_bounds;
  bounds.extend(right_bounds);
  BvhNode& node = nodes[static_cast<std::size_t>(index)];
  node.box = bounds.inflated(box_margin());
  node.left = left;
  node.right = right;
  return index;
}

}  // namespace offsetopt
