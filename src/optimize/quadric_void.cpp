#include "optimize/quadric_void.h"

#include "mass/volume_integrals.h"
#include "util/neumaier_sum.h"

namespace offsetopt {

namespace {

// The integrals of the programme's void, Σ u_i · (cube i), about `origin` (Neumaier sums in cell
// order, so the same for any thread count).
Vector10d occupancy_integrals(const Reachability& reach, bool mid_reading, const Eigen::Vector3d& origin) {
  const CarvableCells& cells = *reach.cells;
  NeumaierSum sums[10];
  const std::vector<std::int64_t>& writable = mid_reading ? cells.mid : cells.inner;
  for (std::size_t i = 0; i < reach.occupancy.size() && i < writable.size(); ++i) {
    const double u = reach.occupancy[i];
    if (u == 0.0) continue;
    const Vector10d cube = cube_integrals(cells.centre(writable[i]), cells.grid.spacing, origin);
    for (int k = 0; k < 10; ++k) sums[k].add(u * cube(k));
  }
  Vector10d out;
  for (int k = 0; k < 10; ++k) out(k) = sums[k].value();
  return out;
}

GoalSpec with_headroom(GoalSpec goal, double headroom) {
  goal.margin *= 1.0 + headroom;
  goal.epsilon *= 1.0 + headroom;
  return goal;
}

// Normalised-frame scale factors of the ten integrals (volume s³, first moments s⁴, second s⁵).
Vector10d in_frame(const Vector10d& integrals, double scale) {
  const int degree[10] = {0, 1, 1, 1, 2, 2, 2, 2, 2, 2};
  Vector10d out;
  for (int k = 0; k < 10; ++k) {
    double factor = scale * scale * scale;
    for (int d = 0; d < degree[k]; ++d) factor *= scale;
    out(k) = integrals(k) * factor;
  }
  return out;
}

}  // namespace

QuadricVoid write_quadric_void(const QuadricVoidInput& input) {
  QuadricVoid out;
  out.attempted = true;
  const GoalSpec aim = with_headroom(input.goal, input.headroom);
  ReachabilityOptions options = input.reach_options;
  options.lowest_cz = true;
  const double scale = 1.0 / input.diagonal;
  for (int round = 0; round <= input.max_rounds; ++round) {
    const Reachability programme = reachability(input.reach->cells, input.outer_integrals, Eigen::Matrix3d::Identity(), aim,
                                                input.ground_z, input.origin, input.diagonal, options);
    if (!programme.ok || !programme.reachable || !programme.optimum) {
      out.message = round == 0 ? "no void of the programme meets the goal with the correction's headroom"
                               : "the programme lost the goal once the contour's moments were counted (round " +
                                     std::to_string(round) + ")";
      break;
    }
    const ContourCavity contoured = contour_cavity(*input.outer, *input.outer_bvh, programme.optimum->about_zero(), input.contour);
    if (!contoured.ok) {
      out.message = "the quadric void could not be contoured: " + contoured.message;
      break;
    }
    const Vector10d model = occupancy_integrals(programme, options.mid_reading, input.origin);
    const Vector10d written = volume_integrals(contoured.cavity, input.origin).values;
    VerifyInput verify = input.verify;
    verify.inner = &contoured.cavity;
    verify.goal_only = true;
    out.verification = verify_offsets(verify);
    const bool last = round == input.max_rounds;
    const bool will_correct = !out.verification.goal_met && !last;
    if (!will_correct) {
      verify.goal_only = false;
      out.verification = verify_offsets(verify);
    }
    ContourRound& entry = out.rounds.emplace_back();
    entry.delta_in_frame = in_frame(written - model - options.void_shift, scale);
    entry.void_volume_offset = model(kIntVolume) + options.void_shift(kIntVolume);
    entry.void_volume_contour = written(kIntVolume);
    entry.grid = Eigen::Vector3i(static_cast<int>(contoured.grid.nx), static_cast<int>(contoured.grid.ny),
                                 static_cast<int>(contoured.grid.nz));
    entry.spacing = contoured.grid.spacing;
    entry.contoured_cells = contoured.active_cells;
    entry.distance_nodes = contoured.distance_nodes;
    entry.shells = contoured.shells;
    entry.shells_filled = contoured.shells_dropped;
    entry.filled_volume = contoured.dropped_volume;
    entry.vertices_moved_for_wall = contoured.vertices_moved_for_wall;
    entry.vertices = static_cast<long long>(contoured.cavity.V.rows());
    entry.faces = static_cast<long long>(contoured.cavity.F.rows());
    entry.goal_met = out.verification.goal_met;
    if (!will_correct) entry.valid = out.verification.valid;
    out.written = contoured.cavity;
    out.quadric = programme.optimum;
    if (!will_correct) break;
    options.void_shift = written - model;
  }
  return out;
}

}  // namespace offsetopt
