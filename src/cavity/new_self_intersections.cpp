#include "cavity/new_self_intersections.h"

#include <algorithm>

#include "geometry/bvh.h"
#include "geometry/intersecting_faces.h"

namespace offsetopt {

NewSelfIntersections new_self_intersections(const Mesh& surface, const std::vector<std::pair<int, int>>& own_pairs,
                                            std::size_t cap, int threads) {
  NewSelfIntersections out;
  BvhOptions options;
  options.threads = threads;
  const TriangleBvh bvh(surface.V, surface.F, options);
  // The cap applies to new pairs: the source's own may be many (a scan with 848 crossings), so
  // the search may find up to their number more before it stops.
  const std::size_t search_cap = cap + own_pairs.size();
  const IntersectingFaces found = self_intersections_in_parts(bvh, search_cap, threads);
  out.truncated = found.truncated;
  for (const auto& pair : found.pairs) {
    if (std::binary_search(own_pairs.begin(), own_pairs.end(), pair)) {
      ++out.own_pairs_kept;
      continue;
    }
    if (out.pairs == 0) {
      out.first_face = pair.first;
      out.second_face = pair.second;
    }
    out.new_pairs.push_back(pair);
    if (static_cast<std::size_t>(++out.pairs) == cap) {
      out.truncated = true;
      break;
    }
  }
  return out;
}

}  // namespace offsetopt
