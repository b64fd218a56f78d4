// Bounding-volume hierarchy over the triangles of a mesh: the spatial index behind ray casting,
// point-in-solid, segment tests and triangle-triangle intersection searches (geometry/ray_cast.h,
// geometry/point_in_solid.h, geometry/intersecting_faces.h). Queries are written as traversals
// over the public node array, so a new query needs no change here.
//
// Build: top-down median split of the face centroids along the longest axis of their bounds,
// ties broken by face index, leaves sorted by face index. The tree is therefore a function of
// the mesh alone (no dependence on the standard library's partial-sort order), and every query
// result is reproducible bit for bit.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "geometry/aabb.h"
#include "mesh/mesh.h"

namespace offsetopt {

struct BvhOptions {
  int leaf_size = 4;  // at most this many faces per leaf; >= 1
  // The root's two subtrees built on two threads when > 1 and the mesh is large enough
  // (kBvhSplitBuildFaces); the tree is the same for any count.
  int threads = 1;

  // Empty when valid, else what is wrong (TriangleBvh's constructor throws it as
  // std::invalid_argument).
  std::string check() const;
};

constexpr int kBvhSplitBuildFaces = 8192;

struct BvhNode {
  Aabb box;         // bounds of every face below, inflated by TriangleBvh::box_margin()
  int left = -1;    // internal node: children indices; leaf: -1
  int right = -1;
  int first = 0;    // leaf: faces leaf_faces()[first, first + count)
  int count = 0;    // 0 for internal nodes
  bool is_leaf() const { return count > 0; }
};

class TriangleBvh {
 public:
  TriangleBvh() = default;
  // Copies V and F (the index owns its geometry, so it stays valid whatever the caller does).
  // Face indices must lie in [0, #V); a mesh without faces gives an empty tree.
  TriangleBvh(const Vertices& V, const Faces& F, const BvhOptions& options = {});

  const Vertices& vertices() const { return V_; }
  const Faces& faces() const { return F_; }
  const std::vector<BvhNode>& nodes() const { return nodes_; }  // root is nodes()[0]
  const std::vector<int>& leaf_faces() const { return leaf_faces_; }
  bool empty() const { return nodes_.empty(); }

  // Read from a copy packed face by face: the mesh's column-major vertex matrix spreads one
  // corner over three cache lines, and the queries read little else.
  Eigen::Vector3d corner(int face, int k) const {
    const double* c = &corners_[static_cast<std::size_t>(9 * face + 3 * k)];
    return Eigen::Vector3d(c[0], c[1], c[2]);
  }
  // The tight box of one face's corners (node boxes are these, merged and inflated).
  const Aabb& face_box(int face) const { return face_boxes_[static_cast<std::size_t>(face)]; }
  // Diagonal of the bounding box of all vertices (the length every tolerance is relative to).
  double diagonal() const { return diagonal_; }
  // How much every node box is grown so that rounding in the slab test never loses a hit that the
  // tolerance-enlarged triangle test would accept.
  double box_margin() const { return 1e-9 * diagonal_; }

  // Calls leaf_visitor(face) for every face whose node boxes pass box_test(const Aabb&), depth
  // first, left before right. The visitor returns false to stop the traversal early.
  template <class BoxTest, class FaceVisitor>
  void traverse(BoxTest&& box_test, FaceVisitor&& face_visitor) const {
    if (nodes_.empty()) return;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const BvhNode& node = nodes_[static_cast<std::size_t>(stack[--top])];
      if (!box_test(node.box)) continue;
      if (node.is_leaf()) {
        for (int k = node.first; k < node.first + node.count; ++k)
          if (!face_visitor(leaf_faces_[static_cast<std::size_t>(k)])) return;
      } else {
        stack[top++] = node.right;
        stack[top++] = node.left;
      }
    }
  }

 private:
  // A face's centroid beside its index, so the median splits read memory in order.
  struct BuildItem {
    double centroid[3];
    int face;
  };
  // The node over items [begin, end) (its index in `nodes`, which it and its subtree are
  // appended to, their leaves' faces to `leaves`), and `bounds` the union of their face boxes.
  int build(std::vector<BuildItem>& items, int begin, int end, int depth, Aabb& bounds, std::vector<BvhNode>& nodes,
            std::vector<int>& leaves) const;
  // Sorts items [begin, end) so that the first half is the lower half along the longest axis of
  // their centroids' bounds, ties by face index: the median split.
  static void split_at_median(std::vector<BuildItem>& items, int begin, int end);

  Vertices V_;
  Faces F_;
  std::vector<BvhNode> nodes_;
  std::vector<int> leaf_faces_;
  std::vector<double> corners_;  // 9 per face: corner 0, 1, 2
  std::vector<Aabb> face_boxes_;
  double diagonal_ = 0.0;
  int leaf_size_ = 4;
};

// Visits every (face of a, face of b) pair of leaves whose boxes overlap, below the node pairs
// `start` (popped last first; {{0, 0}} for the whole trees). With `same` (a and b one tree) the
// pairs (i, j) and (j, i) are visited once and no face meets itself. The larger box is split
// first; the order is a function of the trees alone. visit(f, g) returns false to stop. With
// `skip_apart`, a face of a leaf of `a` whose own box misses the other leaf's box meets none of
// its faces' boxes and is not visited with them (the visits left keep their order).
template <class Visitor>
void traverse_face_pairs(const TriangleBvh& a, const TriangleBvh& b, bool same, std::vector<std::pair<int, int>> start,
                         Visitor&& visit, bool skip_apart = false) {
  if (a.empty() || b.empty()) return;
  const auto& na = a.nodes();
  const auto& nb = b.nodes();
  // A stack written by index: each step pushes at most three pairs, and a descent of at most 61
  // levels in each tree keeps it below `start` + 256 (grown if ever needed).
  std::vector<std::pair<int, int>> stack = std::move(start);
  std::size_t top = stack.size();
  stack.resize(top + 256);
  auto push = [&stack, &top](int i, int j) {
    if (top == stack.size()) stack.resize(2 * stack.size());
    stack[top++] = {i, j};
  };
  while (top > 0) {
    const auto [ia, ib] = stack[--top];
    const BvhNode& x = na[static_cast<std::size_t>(ia)];
    const BvhNode& y = nb[static_cast<std::size_t>(ib)];
    if (!x.box.overlaps(y.box)) continue;
    if (same && ia == ib) {
      if (x.is_leaf()) {
        for (int i = x.first; i < x.first + x.count; ++i)
          for (int j = i + 1; j < x.first + x.count; ++j)
            if (!visit(a.leaf_faces()[static_cast<std::size_t>(i)], a.leaf_faces()[static_cast<std::size_t>(j)])) return;
      } else {
        push(x.right, x.right);
        push(x.left, x.right);
        push(x.left, x.left);
      }
      continue;
    }
    if (x.is_leaf() && y.is_leaf()) {
      for (int i = x.first; i < x.first + x.count; ++i) {
        const int f = a.leaf_faces()[static_cast<std::size_t>(i)];
        if (skip_apart && !a.face_box(f).overlaps(y.box)) continue;
        for (int j = y.first; j < y.first + y.count; ++j)
          if (!visit(f, b.leaf_faces()[static_cast<std::size_t>(j)])) return;
      }
      continue;
    }
    const bool split_a = !x.is_leaf() && (y.is_leaf() || (x.box.hi - x.box.lo).squaredNorm() >= (y.box.hi - y.box.lo).squaredNorm());
    if (split_a) {
      push(x.right, ib);
      push(x.left, ib);
    } else {
      push(ia, y.right);
      push(ia, y.left);
    }
  }
}

}  // namespace offsetopt
