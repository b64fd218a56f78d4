// The faces of a TriangleBvh near a small region, gathered once (one tree walk) and then searched
// for the nearest face of many points of that region (a block of grid nodes, the points of a
// grid edge), where a tree walk per point would cost several times more.
//
// nearest() returns exactly what closest_point(bvh, p, max_distance) returns (same face, point and
// distance, to the last bit: the same triangle arithmetic and the same tie rule, lowest face index
// at equal squared distance), for ANY p: it certifies its own answer (every face nearer than the
// answer, or within max_distance when there is none, lies within `radius` of the centre, so it is
// on the list) and asks closest_point itself when it cannot. The gathering's centre and radius
// therefore only decide the cost, never a value.
#pragma once
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/closest_point.h"

namespace offsetopt {

class FaceShortlist {
 public:
  // More faces than this near one region (a fine mesh against a thick wall: at 10^6 vertices the
  // lists held thousands, and sorting them cost more than the tree walks they replaced, contour
  // 6.7 -> 16.1 s) and the region is left to closest_point: nearest() asks it for every point.
  static constexpr std::size_t kMaxFaces = 1024;

  // The faces whose own box lies within `radius` of `centre` (none kept beyond kMaxFaces).
  void gather(const TriangleBvh& bvh, const Eigen::Vector3d& centre, double radius);
  // Whether a ball (centre, reach) lies within the gathered one, with room for rounding: points
  // of that ball whose answer is no farther than what is left are answered from the list.
  bool covers(const Eigen::Vector3d& centre, double reach) const;
  // closest_point(bvh, p, max_distance). `hint`: a face likely nearest (or -1), measured first.
  ClosestPoint nearest(const TriangleBvh& bvh, const Eigen::Vector3d& p,
                       double max_distance = std::numeric_limits<double>::infinity(), int hint = -1) const;
  bool empty() const { return !gathered_; }
  bool overflowed() const { return overflowed_; }  // the last gather met more than kMaxFaces
  std::size_t size() const { return faces_.size(); }
  // Queries answered by closest_point because the list could not certify them.
  mutable long fallbacks = 0;

 private:
  const TriangleBvh* bvh_ = nullptr;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
  double radius_ = 0.0;
  bool gathered_ = false;
  bool overflowed_ = false;  // more than kMaxFaces near the region: nearest() is closest_point
  struct Entry {
    double from_centre;  // the face box's distance from the centre
    int face;
  };
  std::vector<Entry> faces_;
  double stop_slack_ = 0.0;
};

}  // namespace offsetopt
