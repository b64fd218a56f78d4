// offsetopt basis: the manifold-harmonic eigenpairs of a mesh (spectral/manifold_harmonics.h),
// as a JSON report, optionally the vectors (.npy or .csv), a PLY to look at one of them, and the
// matrices (Matrix Market) for comparisons with other solvers.
#include <chrono>
#include <climits>
#include <cstdio>
#include <string>

#include "cli/cli_support.h"
#include "cli/commands.h"
#include "geometry/cotan_laplacian.h"
#include "geometry/lumped_mass.h"
#include "io/basis_files.h"
#include "io/json.h"
#include "meshio/load_mesh.h"
#include "spectral/manifold_harmonics.h"

namespace offsetopt::cli {

namespace {

const CommandHelp kHelp = {
    "usage: offsetopt basis MESH --k N [options]\n"
    "\n"
    "The k smallest eigenpairs of the cotan Laplacian (manifold harmonics), by a shift-invert\n"
    "block Lanczos solver. The JSON report goes to stdout unless --json names a file.\n",
    {
        {"--k", "N", "none (required)", OptionRange::integer_up_to(1, "#vertices - 1"), "number of eigenpairs", "4"},
        {"--basis", "KIND", "mass", "mass | laplacian",
         "'mass': L phi = lambda M phi, phi'M phi = 1, with the lumped mass M; 'laplacian': L phi = lambda phi, |phi| = 1 (the paper)",
         "laplacian"},
        {"--json", "FILE|-", "- (stdout)", "a path, or - for stdout", "where the report goes", "basis.json"},
        {"--vectors", "FILE", "none", "a path ending in .npy or .csv",
         "write the eigenvectors: FILE.npy (NumPy, float64, shape (#V, k), column j = eigenvector j) or FILE.csv (header phi_0..phi_{k-1}, one row per vertex, shortest round-trip numbers)",
         "vectors.npy"},
        {"--ply", "FILE", "none", "a path ending in .ply",
         "write the mesh as binary PLY with eigenvector J as per-vertex 'quality' and a blue-white-red colour", "basis.ply"},
        {"--ply-vector", "J", "1 (the first non-constant; 0 when k = 1)", OptionRange::integer_up_to(0, "k - 1"), "which eigenvector --ply shows", "0"},
        {"--tol", "T", "1e-10", OptionRange::real(1e-15, 1e-2), "convergence: |L phi - lambda M phi| <= T |L|inf |phi|", "1e-8"},
        {"--block-size", "B", "6", OptionRange::integer(1, 64), "Lanczos block size (at least the largest eigenvalue multiplicity)", "4"},
        {"--threads", "N", "0 (min(2, cores))", OptionRange::integer(0, 64), "threads for the iteration; the results are the same bits for any N",
         "1"},
        {"--matrices", "PREFIX", "none", "a path prefix",
         "also write PREFIX_L.mtx and PREFIX_M.mtx (Matrix Market), the exact matrices solved, for comparisons with other eigensolvers",
         "m"},
        {"--quiet", "", "off", "flag", "no progress or warnings on stderr", ""},
        {"-h, --help", "", "off", "flag", "show this help", ""},
    },
    "report fields: eigenvalues (ascending), residuals (relative, as --tol), status, converged,\n"
    "iterations (block steps), operator_applications (vectors through (L + sM)^-1), seconds\n"
    "(ordering, factorisation and iterations), factor_seconds, total_seconds (reading, assembly\n"
    "and solve). Exit 0 when every pair converged, 3 when not (outputs still written).\n"};

using Clock = std::chrono::steady_clock;

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

Json numbers(const Eigen::VectorXd& values) {
  Json array = Json::array();
  for (Eigen::Index i = 0; i < values.size(); ++i) array.push_back(Json(values(i)));
  return array;
}

}  // namespace

int run_basis(const Args& args) {
  const Clock::time_point start = Clock::now();
  std::string mesh_path, json_path = "-", vectors_path, ply_path, matrices_prefix;
  int k = 0, ply_vector = -1;
  bool quiet = false;
  ManifoldHarmonicsOptions options;
  ArgCursor cursor(args);
  while (!cursor.done()) {
    const std::string& arg = cursor.next();
    require_known_option("basis", kHelp.options, arg);
    if (arg == "--help" || arg == "-h") {
      write_text("-", format_help(kHelp));
      return kExitOk;
    } else if (arg == "--k") {
      k = parse_integer_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--basis") {
      const std::string& kind = cursor.value_of(arg);
      if (!parse_basis_kind(kind, options.kind))
        throw UsageError("--basis expects 'laplacian' or 'mass', got '" + kind + "'");
    } else if (arg == "--json") {
      json_path = cursor.value_of(arg);
    } else if (arg == "--vectors") {
      vectors_path = cursor.value_of(arg);
      if (!ends_with(vectors_path, ".npy") && !ends_with(vectors_path, ".csv"))
        throw UsageError("--vectors " + vectors_path + ": the name must end in .npy or .csv");
    } else if (arg == "--ply") {
      ply_path = cursor.value_of(arg);
      if (!ends_with(ply_path, ".ply")) throw UsageError("--ply " + ply_path + ": the name must end in .ply");
    } else if (arg == "--ply-vector") {
      ply_vector = parse_integer_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--tol") {
      options.lanczos.tolerance = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--block-size") {
      options.lanczos.block_size = parse_integer_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--threads") {
      options.lanczos.threads = parse_integer_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--matrices") {
      matrices_prefix = cursor.value_of(arg);
    } else if (arg == "--quiet") {
      quiet = true;
    } else if (!arg.empty() && arg[0] == '-' && arg != "-") {
      throw UsageError("basis: unknown option '" + arg + "' (try 'offsetopt basis --help')");
    } else if (mesh_path.empty()) {
      mesh_path = arg;
    } else {
      throw UsageError("basis: unexpected argument '" + arg + "' (one MESH only)");
    }
  }
  if (mesh_path.empty()) throw UsageError("basis: missing MESH (try 'offsetopt basis --help')");
  if (k == 0) throw UsageError("basis: --k N is required, " + mesh_path);
  if (ply_vector >= 0 && ply_path.empty()) throw UsageError("--ply-vector needs --ply FILE");
  if (ply_vector >= k) throw UsageError("--ply-vector " + std::to_string(ply_vector) + " must be below --k " + std::to_string(k));
  const std::vector<std::string> inputs = {mesh_path};
  for (const std::string* output : {&json_path, &vectors_path, &ply_path})
    if (!output->empty()) refuse_overwriting_input(*output, inputs);
  if (!matrices_prefix.empty()) {
    refuse_overwriting_input(matrices_prefix + "_L.mtx", inputs);
    refuse_overwriting_input(matrices_prefix + "_M.mtx", inputs);
  }

  const LoadedMesh loaded = load_input(mesh_path);
  print_warnings(loaded.warnings, quiet);
  const Mesh& mesh = loaded.mesh;
  const Eigen::Index n = mesh.vertex_count();
  if (k >= n)
    throw UsageError("--k " + std::to_string(k) + " must be below the number of vertices (" + std::to_string(n) +
                     "), " + mesh_path);

  const LanczosResult result = manifold_harmonics(mesh, k, options);
  const double total_seconds = seconds_since(start);
  if (result.status == LanczosStatus::invalid_input) throw UsageError(mesh_path + ": " + result.message);
  if (result.status == LanczosStatus::factorization_failed) {
    std::fprintf(stderr, "Error: %s: %s\n", mesh_path.c_str(), result.message.c_str());
    return kExitInternal;
  }
  const double solve_seconds = result.factor_seconds + result.iteration_seconds;
  if (!quiet) {
    std::fprintf(stderr, "basis: %lld vertices, k = %d (%s): %s, %ld operator applications in %d block steps; factor %.3f s, iterations %.3f s\n",
                 static_cast<long long>(n), k, to_string(options.kind), to_string(result.status),
                 result.operator_applications, result.iterations, result.factor_seconds, result.iteration_seconds);
  }

  Json report = Json::object();
  report.set("command", "basis");
  report.set("mesh", mesh_path);
  report.set("vertices", static_cast<long long>(n));
  report.set("faces", static_cast<long long>(mesh.face_count()));
  report.set("k", k);
  report.set("basis", to_string(options.kind));
  report.set("tolerance", options.lanczos.tolerance);
  report.set("status", to_string(result.status));
  if (!result.message.empty()) report.set("message", result.message);
  report.set("converged", result.converged);
  report.set("solver", result.dense ? "dense" : "block-lanczos");
  report.set("block_size", result.dense ? 0 : std::min<int>(options.lanczos.block_size, static_cast<int>(n)));
  report.set("threads", result.threads);
  report.set("iterations", result.iterations);
  report.set("restarts", result.restarts);
  report.set("operator_applications", result.operator_applications);
  report.set("shift", result.shift);
  report.set("matrix_norm", result.matrix_norm);
  report.set("factor_nonzeros", result.factor_nonzeros);
  report.set("eigenvalues", numbers(result.eigenvalues));
  report.set("residuals", numbers(result.residuals));
  report.set("seconds", solve_seconds);
  report.set("factor_seconds", result.factor_seconds);
  report.set("total_seconds", total_seconds);
  write_text(json_path, report.dump(2) + "\n", inputs);

  if (!vectors_path.empty()) {
    write_text(vectors_path,
               ends_with(vectors_path, ".npy") ? eigenvectors_npy(result.eigenvectors) : eigenvectors_csv(result.eigenvectors),
               inputs);
  }
  if (!ply_path.empty()) {
    const int column = ply_vector >= 0 ? ply_vector : (k > 1 ? 1 : 0);
    write_text(ply_path, scalar_ply(mesh, result.eigenvectors.col(column)), inputs);
  }
  if (!matrices_prefix.empty()) {
    const Eigen::SparseMatrix<double> L = cotan_laplacian(mesh.V, mesh.F, options.cotan);
    Eigen::SparseMatrix<double> M(n, n);
    if (options.kind == BasisKind::mass) {
      const Eigen::VectorXd mass = lumped_mass(mesh.V, mesh.F);
      std::vector<Eigen::Triplet<double>> diagonal;
      for (Eigen::Index i = 0; i < n; ++i) diagonal.emplace_back(i, i, mass(i));
      M.setFromTriplets(diagonal.begin(), diagonal.end());
    } else {
      M.setIdentity();
    }
    write_text(matrices_prefix + "_L.mtx", matrix_market(L), inputs);
    write_text(matrices_prefix + "_M.mtx", matrix_market(M), inputs);
  }
  return result.status == LanczosStatus::converged ? kExitOk : kExitGoalNotMet;
}

}  // namespace offsetopt::cli
