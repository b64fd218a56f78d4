// Moment-space reachability (docs/design.md "Reachability: what any void can do"): can ANY void (any
// set of carvable cells, cavity/carvable_cells.h) meet the goal as the mesh is posed, with how much
// to spare, and if not, a proof.
//
// The solid's 10 integrals are affine in the occupancy u ∈ [0,1] of the cells (void cells remove
// their cube's integrals, --outer band cells add them). Every goal's rows are affine in u, or a
// margin over the mass N(u) ≥ t·D(u) (GoalSpec, shape/goal.h, in input units):
//   stand          one row per support edge: ∫(n_e·(x − a_e)) ≥ t·M (distance inside the edge);
//   stand-filled   those rows, and the same for the filled object (liquid of fill_density in the void);
//   roly-poly      |∫(x − x0)| ≤ τ·M, |∫(y − y0)| ≤ τ·M; ∫(z0 − z) ≥ t·M (below the sphere centre);
//   float          |void − (1 − ρ)V| ≤ τ_v; the two axis rows about the centre of buoyancy;
//                  ∫(cb_z − z) ≥ t·M (below the centre of buoyancy); no --outer band;
//   spin           axis rows at the tip, |∫zx − x0∫z|, |∫yz − y0∫z| ≤ τ_I ∫((x−x0)² + (y−y0)²),
//                  and "Izz largest" ∫(e·(r − tip))² ≥ ∫(z − c)² for `spin_directions` horizontal e,
//                  at `spin_levels` heights c (sufficient for c = cz): feasibility only;
//   volume         the target at most the carvable volume (no programme).
// τ is axis_tolerance × the diagonal for the claim "reachable" (its hypot stays inside the
// verification's 1e-4 × diagonal) and the verification's own bounds for the claim "unreachable".
//
// The largest margin t is found by Dinkelbach iterations (one LP each, optim/bounded_simplex.h:
// max z s.t. N_j − t D_j ≥ z, t ← min_j N_j/D_j), the lowest centre of mass height with the goal
// met at the user's margin likewise (min ∫z / M). Each LP starts on blocks of block³ cells and
// splits a block into its cells wherever the duals say the cells disagree (a reduced cost of the
// wrong sign, or a fractional block), so the answer is the optimum over single cells.
// The LP duals w ≥ 0 combine the rows into one functional Σ w_k R_k(u) = F0 + ∫_void q_v + ∫_band q_b
// with q a quadric in (1, x, y, z, x², y², z², xy, yz, zx): the optimal void is {q < 0} ∩ carvable
// (q = −q_v; Hafner et al. 2024, "Spin-It Faster"). For an unreachable goal the certificate is that
// F0 plus, over every outer cell, the cell's volume times an upper bound of q_v on the cube (value,
// gradient and Hessian bounds at the centre) is negative: no void of any shape keeping the wall can
// meet every row. Where whole outer cells decide nothing, the outer reading is run again with each
// cell near the wall counted by its share (cavity/wall_deep_shares.h): its column scaled, its
// bound the share times the cube's volume times that upper bound.
//
// Sign conventions: margins positive when met (inside the polygon, below the centre). Everything
// reported is in input units; lowest_cz is the height over the ground plane (ground_z).
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cavity/carvable_cells.h"
#include "geometry/bvh.h"
#include "mass/volume_integrals.h"
#include "mesh/mesh.h"
#include "optim/bounded_simplex.h"
#include "shape/goal.h"

namespace offsetopt {

struct ReachabilityOptions {
  double wall = 0.0;                 // input units, > 0
  double outer_max = 0.0;            // --outer: input units, > 0
  double ground_tol = 0.0;           // input units, >= 0
  bool outer = false;                // the band adds material
  // The cells: spacing wall / cells_per_wall (the contour's by default; finer grids lose less of
  // the carvable region to whole cells, at a price in time); their nodes keep the contour's
  // node test at the contour's spacing (cavity/contour_cavity.h, cavity_node_level).
  double cells_per_wall = 1.5;
  double contour_cells_per_wall = 1.5;
  double margin_cells = 0.0;         // as OptimizeOptions::cavity_margin_cells
  double node_margin = -1.0;         // input units; negative: the contour's, as above
  std::int64_t max_nodes = std::int64_t{1} << 25;
  // Cells per LP block side: 1, 2, 4, 8 or 16 (split by octants). 8 rather than 4: a programme
  // from a cold start pivots about once per column it carves (roly-poly's near-equality axis rows
  // made that 8 pivots per column, up to the iteration cap), and the splits find the cells anyway.
  int block = 8;
  int max_dinkelbach = 30;           // LPs per ratio search
  int max_refinements = 40;          // block splits per LP
  // Halvings of a shell cell into sub-cubes when the generous reading counts it in part
  // (cavity/wall_deep_shares.h), in [0, 6]; 0: whole cells only. 3: sub-cubes an eighth of a
  // cell (a twelfth of a wall at the contour's spacing); the shares then sum to within 0.07 of a
  // wall's layer of the exact region on a box (bench/cavity/wall_deep_shares.sh for the times).
  int share_levels = 3;
  // The generous reading straight with the shell in part, not whole cells first: for finer cells
  // after the contour's counted in part decided nothing (whole cells half as large reach 0.29 of a
  // wall past it, the contour's in part about 0.07: they would not decide either).
  bool shell_in_part_first = false;
  bool lowest_cz = true;             // also the lowest centre of mass (stand, stand-filled, roly-poly, float)
  double axis_tolerance = 0.5e-4;    // fraction of the diagonal, the "reachable" reading's τ
  int spin_levels = 11, spin_directions = 24;
  int threads = 2;
  BoundedSimplexOptions lp = lp_defaults();
  // Read "reachable", the margins, the lowest centre of mass and the occupancy on the mid cells
  // (CarvableCells::mid: the contour's void at the cell scale) instead of the inner ones: the
  // estimate of the best void at the exact wall, and the programme the quadric void is written
  // from. The claim "unreachable" is always read on the outer cells.
  bool mid_reading = false;
  // The generous reading's margin search to its optimum even once it clears the user's margin.
  // Cleared, no certificate can come of it, so the claim stays undecided and the optimum would
  // only bound best_margin_upper: by default the search stops there (the demo bottle standing
  // filled with --outer: 18 programmes instead of 32), and a run that misses the goal asks again
  // with this set, for the bracket its refusal prints.
  bool bound_undecided = false;
  // Volume: where the ball that holds the target starts (Reachability::find_optimum). None: at
  // the writable cell nearest their centroid. A line (a channel's axis, pointing out of the object
  // into the opening): at the writable cell farthest along it of those within a cell of it, so
  // that the channel cut to the void is short; the centroid's cell when none is.
  struct Line {
    Eigen::Vector3d point = Eigen::Vector3d::Zero(), direction = Eigen::Vector3d::UnitZ();
  };
  std::optional<Line> volume_start;

  static BoundedSimplexOptions lp_defaults() {
    BoundedSimplexOptions o;  // rows are scaled by the volume: values O(1), a cell's column O(1/#cells)
    o.feasibility_tolerance = 1e-11;
    o.optimality_tolerance = 1e-14;
    o.pivot_tolerance = 1e-10;
    o.dual = true;  // a Dinkelbach step or a block split moves thousands of cells at once
    return o;
  }
  static ReachabilityOptions defaults() { return ReachabilityOptions(); }
  std::string check() const;
};

// q(p) = Σ_k coefficients_k m_k(p − origin) on the monomials m = [1, x, y, z, x², y², z², xy, yz, zx]
// (mass/volume_integrals.h order), input units.
struct Quadric {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Vector10d coefficients = Vector10d::Zero();
  // The same quadric on the monomials of p itself (origin 0), as cavity/contour_cavity.h takes it.
  Vector10d about_zero() const;
};

struct ReachCertificate {
  bool present = false;
  bool proves = false;               // the bound is negative: no void reaches the goal
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // q(p) = Σ_k quadric_k m_k(p − origin), input units
  Vector10d quadric = Vector10d::Zero();             // void = {q < 0}; scale arbitrary
  // Σ w_k R_k(void) = constant − ∫_void q (input units, up to one positive factor): the rows met
  // would make it >= 0.
  double constant = 0.0;
  double bound = 0.0;                // upper bound of Σ w_k R_k over every void (rows / volume)
  int cells_checked = 0;
};

struct Reachability {
  bool ok = false;
  std::string message;               // why not, when !ok
  bool reachable = false;            // on the inner reading: a void the tool can write meets the goal
  bool decided = false;              // reachable, or unreachable with a certificate that proves it
  std::optional<double> best_margin;        // inner reading, input units (none: spin, volume)
  std::optional<double> best_margin_upper;  // outer reading (computed when not reachable), when it bounds every void
  // The outer reading's margin as found, even when it is not a bound (a search stopped short, or
  // below the mid reading's best): it ranks the remedies and names the ones that may reach.
  std::optional<double> outer_margin_found;
  std::string binding;               // the row that limits the best margin ("support edge 3")
  std::optional<double> lowest_cz;   // over the ground, input units, goal met at the user's margin
  // The void of that lowest centre of mass: {q < 0} ∩ the inner cells (all but a few fractional
  // cells of `occupancy`); set with lowest_cz.
  std::optional<Quadric> optimum;
  // Spin: `optimum` is found only when asked, by calling this on the programme (or a copy): it
  // sets optimum, occupancy and band_occupancy, and counts its programmes in lps. The offset void
  // mostly meets spin, and the optimum costs many times the feasible void (the demo top: 18,506
  // simplex iterations against 107). Volume: the same, for the ball about the cells' middle that
  // holds the target (no programme: the goal places no centre of mass). Empty otherwise.
  std::function<void(Reachability&)> find_optimum;
  ReachCertificate certificate;      // unreachable: the proof; reachable: the optimum's quadric
  std::shared_ptr<const CarvableCells> cells;
  std::vector<double> occupancy;     // per cells->inner (or ->mid): the LP's optimal void (lowest cz if computed);
                                     // empty when blocks were split after the best iterate
  std::vector<double> band_occupancy;  // per cells->band_inner
  double carvable_volume = 0.0, carvable_volume_outer = 0.0, band_volume = 0.0;
  // The generous reading counted its shell cells in part (cavity/wall_deep_shares.h): the whole
  // cells left the answer open. For volume, carvable_volume_outer is then the shares' sum.
  bool partial_cells = false;
  int lps = 0;
  long long lp_iterations = 0;
  long long pricing_passes = 0;
  int columns = 0;                   // of the last LP (blocks and split cells)
};

// Computes the shares of the generous cells a void may hold (cavity/wall_deep_shares.h), on demand.
using ShareSource = std::function<std::vector<double>()>;

// The goal in input units, as posed (support polygon CCW, GoalSpec's fields); ground_z the ground
// plane; `origin` a point near the object (the ground contact centroid on the ground).
Reachability reachability(const Mesh& input, const TriangleBvh& input_bvh, const GoalSpec& goal, double ground_z,
                          const Eigen::Vector3d& origin, const ReachabilityOptions& options);

// The same on cells already found for the input as given, for the input rotated by `rotation`
// (another face down: the cells do not depend on the pose, a rotated cube's integrals are the
// cube's at the rotated centre). `goal`, `ground_z` and `origin` are in the rotated pose;
// `input_integrals` of the input as given; `diagonal` the input's. `shares`, when set, gives
// cavity/wall_deep_shares.h's shares of cells->outer, asked for at most once and only where whole
// cells decide nothing (not with the --outer band); the overload above sets it.
Reachability reachability(std::shared_ptr<const CarvableCells> cells, const VolumeIntegrals& input_integrals,
                          const Eigen::Matrix3d& rotation, const GoalSpec& goal, double ground_z,
                          const Eigen::Vector3d& origin, double diagonal, const ReachabilityOptions& options,
                          const ShareSource& shares = {});

}  // namespace offsetopt
