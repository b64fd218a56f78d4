// Reachability (cavity/reachability.h) on one mesh as posed, with the tool's default lengths
// (wall 1%, margin 0.2%, ground tolerance 0.1% of the diagonal, outer_max 2%): seconds for the
// cells and for the programmes, and the answers, one line of figures per run.
// usage: bench_reachability MESH GOAL [--fluid-density R] [--fill-density R] [--outer] [--threads N] [--mid]
//        [--no-cells-alone] (skip the separate timing of the cells, e.g. under callgrind)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cavity/carvable_cells.h"
#include "cavity/reachability.h"
#include "mass/mass_properties.h"
#include "mass/stability.h"
#include "meshio/load_mesh.h"

using namespace offsetopt;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_reachability MESH GOAL [--fluid-density R] [--fill-density R] [--outer] [--threads N] [--mid] [--no-cells-alone]\n");
    return 2;
  }
  GoalSpec goal;
  if (!parse_goal_kind(argv[2], goal.kind)) return 2;
  goal.fluid_density = 0.8;
  ReachabilityOptions o;
  bool cells_alone = true;
  Eigen::Vector3d center(0, 0, -1e300);  // roly-poly: the report's goal.sphere_center
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--outer") o.outer = true;
    else if (a == "--fluid-density" && i + 1 < argc) goal.fluid_density = std::atof(argv[++i]);
    else if (a == "--fill-density" && i + 1 < argc) goal.fill_density = std::atof(argv[++i]);
    else if (a == "--threads" && i + 1 < argc) o.threads = std::atoi(argv[++i]);
    else if (a == "--cells-per-wall" && i + 1 < argc) o.cells_per_wall = std::atof(argv[++i]);
    else if (a == "--node-margin-walls" && i + 1 < argc) o.node_margin = std::atof(argv[++i]);  // × wall, below
    else if (a == "--block" && i + 1 < argc) o.block = std::atoi(argv[++i]);
    else if (a == "--mid") o.mid_reading = true;  // as optimize reads it (reachability_stage)
    else if (a == "--no-cells-alone") cells_alone = false;
    else if (a == "--center" && i + 1 < argc) std::sscanf(argv[++i], "%lf,%lf,%lf", &center.x(), &center.y(), &center.z());
  }
  const Mesh mesh = load_mesh(argv[1]).mesh;
  const Eigen::Vector3d lo = mesh.V.colwise().minCoeff().transpose(), hi = mesh.V.colwise().maxCoeff().transpose();
  const double diag = (hi - lo).norm();
  o.wall = 0.01 * diag;
  if (o.node_margin >= 0.0) o.node_margin *= o.wall;
  o.outer_max = 0.02 * diag;
  o.ground_tol = 0.001 * diag;
  const Vector10d P = mass_properties(mesh);
  StabilityOptions so;
  so.ground_tol = o.ground_tol;
  const Stability st = compute_stability(mesh, Eigen::Vector3d(P(kCx), P(kCy), P(kCz)), so);
  goal.support_polygon = st.support_polygon;
  goal.margin = goal.epsilon = 0.002 * diag;
  Eigen::Index lowest = 0;
  mesh.V.col(2).minCoeff(&lowest);
  goal.axis_point = mesh.V.row(lowest).transpose();
  if (goal.kind == GoalKind::roly_poly) goal.axis_point = center.z() > -1e299 ? center : Eigen::Vector3d(goal.axis_point + Eigen::Vector3d(0, 0, 0.25 * (hi.z() - lo.z())));
  if (goal.kind == GoalKind::volume) goal.target_volume = 0.3 * P(kMass);
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : st.support_polygon) centroid += p;
  centroid /= static_cast<double>(std::max<std::size_t>(1, st.support_polygon.size()));
  const TriangleBvh bvh(mesh.V, mesh.F);
  if (cells_alone) {
    const auto t0 = std::chrono::steady_clock::now();
    CarvableCellsOptions co;
    co.wall = o.wall;
    co.threads = o.threads;
    const CarvableCells cells = carvable_cells(mesh, bvh, co);
    std::printf("cells alone: %.3f s, grid %lld x %lld x %lld\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), (long long)cells.grid.nx,
                (long long)cells.grid.ny, (long long)cells.grid.nz);
  }
  const auto start = std::chrono::steady_clock::now();
  const Reachability r = reachability(mesh, bvh, goal, st.ground_z, Eigen::Vector3d(centroid.x(), centroid.y(), st.ground_z), o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (r.cells) std::printf("band cells %zu strict, %zu generous; void %zu / %zu\n", r.cells->band_inner.size(), r.cells->band_outer.size(), r.cells->inner.size(), r.cells->outer.size());
  auto opt = [](const std::optional<double>& v) { return v ? std::to_string(*v) : std::string("none"); };
  std::printf("%s\t%s\tvertices %lld\tseconds %.3f\tok %d\treachable %d\tdecided %d\tbest_margin %s\tupper %s\tmargin %.4g\t"
              "binding '%s'\tlowest_cz %s\tinput_cz %.4g\tcells %zu/%zu\tqueries %lld\tlps %d\titerations %lld\tpasses %lld\tcolumns %d\tproves %d %s\n",
              argv[1], argv[2], static_cast<long long>(mesh.V.rows()), seconds, r.ok, r.reachable, r.decided,
              opt(r.best_margin).c_str(), opt(r.best_margin_upper).c_str(), goal.margin, r.binding.c_str(),
              opt(r.lowest_cz).c_str(), P(kCz) - st.ground_z, r.cells ? r.cells->inner.size() : 0,
              r.cells ? r.cells->outer.size() : 0, r.cells ? static_cast<long long>(r.cells->distance_queries) : 0LL, r.lps,
              r.lp_iterations, r.pricing_passes, r.columns, r.certificate.proves, r.message.c_str());
  return 0;
}
