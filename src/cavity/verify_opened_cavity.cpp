#include "cavity/verify_opened_cavity.h"

#include <array>
#include <map>
#include <vector>
#include <utility>

#include "cavity/printable_solid.h"
#include "cavity/round_for_output.h"
#include "geometry/bvh.h"
#include "geometry/intersecting_faces.h"
#include "mass/volume_integrals.h"

namespace offsetopt {
namespace {

// Directed edges that are not used exactly once with their opposite used exactly once, on
// positions rather than indices (a reader merges equal points, as CGAL's does).
long long unmatched_edges(const Mesh& mesh) {
  std::map<std::array<double, 3>, int> position;
  std::vector<int> id(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    id[static_cast<std::size_t>(v)] = position.emplace(std::array<double, 3>{mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2)},
                                                       static_cast<int>(position.size())).first->second;
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      ++directed[{id[static_cast<std::size_t>(mesh.F(f, c))], id[static_cast<std::size_t>(mesh.F(f, (c + 1) % 3))]}];
  long long bad = 0;
  for (const auto& [edge, count] : directed) {
    const auto opposite = directed.find({edge.second, edge.first});
    if (count != 1 || opposite == directed.end() || opposite->second != 1) ++bad;
  }
  return bad;
}

}  // namespace

VerifiedOpenedCavity verify_opened_cavity(const Mesh& outer, const Mesh& cavity, const OpenCavityOptions& options,
                                          VerifyInput input, const Verification& uncut, StoredPrecision precision) {
  VerifiedOpenedCavity out;
  out.verification = uncut;
  out.opened = open_cavity(outer, cavity, options);
  if (!out.opened.ok) {
    out.verification.valid = false;
    out.verification.failures.insert(out.verification.failures.begin(), "openings: " + out.opened.message);
    return out;
  }
  const RoundedForOutput rounded = round_for_output(out.opened.solid, Mesh(), {}, precision, input.threads);
  out.solid = rounded.outer;
  out.rounding_new_pairs = rounded.outer_new_pairs;
  // Closed and oriented as read back, but for what the input had (a pinched input keeps its pinch).
  out.closed = out.solid.F.rows() > 0 && unmatched_edges(out.solid) <= unmatched_edges(hollow_solid(outer, cavity));
  const TriangleBvh bvh(out.solid.V, out.solid.F);
  const std::size_t cap = 100000;
  for (const auto& [f, g] : self_intersections(bvh, cap).pairs)
    if (out.opened.source_face[static_cast<std::size_t>(f)] < 0 || out.opened.source_face[static_cast<std::size_t>(g)] < 0)
      ++out.new_pairs;
  out.void_surfaces = hollow_solid(outer, out.solid);
  const Eigen::Vector3d origin = mean_vertex(outer);
  out.void_volume = volume_integrals(out.void_surfaces, origin).values(kIntVolume);
  bool liquid_ok = true;
  if (input.goal.kind == GoalKind::stand_filled && out.opened.spill_height) {
    Mesh outer_below, solid_below;
    liquid_ok = cut_by_plane(outer, 2, *out.opened.spill_height, false, outer_below) &&
                cut_by_plane(out.solid, 2, *out.opened.spill_height, false, solid_below);
    if (liquid_ok) {
      out.liquid = hollow_solid(outer_below, solid_below);
      out.liquid_volume = volume_integrals(*out.liquid, origin).values(kIntVolume);
    }
  }
  input.outer = &outer;
  input.inner = &out.void_surfaces;
  input.liquid = out.liquid ? &*out.liquid : nullptr;
  input.goal_only = true;
  input.rounding = nullptr;
  const Verification goal = verify_offsets(input);
  Verification& v = out.verification;
  v.goal_met = goal.goal_met;
  v.goal = goal.goal;
  v.failures = goal.failures;
  auto refuse = [&](const std::string& why) {
    v.valid = false;
    v.failures.push_back(why);
  };
  v.valid = uncut.valid;
  if (!out.closed) refuse("openings: the cut solid is not one closed, oriented 2-manifold");
  if (out.new_pairs > 0) refuse("openings: " + std::to_string(out.new_pairs) + " face pairs of the cut intersect");
  if (out.rounding_new_pairs > 0)
    refuse("openings: rounding the cut solid to the output's precision made " + std::to_string(out.rounding_new_pairs) +
           " face pairs intersect");
  if (!liquid_ok) refuse("openings: the liquid below the spill height could not be cut");
  return out;
}

}  // namespace offsetopt
