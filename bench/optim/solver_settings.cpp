// Solver settings judged on many meshes, not on six: the whole optimise pipeline
// (optimize_offsets, the CLI's defaults, float32 output as an STL file gets) on every mesh of a
// folder, once with the default solver settings and once per variant given, printing per setting
// the evaluations summed over the meshes, how many runs verified, and how far the objective moved.
// A figure, not a test. Why it exists: an inner tolerance of 1e-3 saved 14% of the six demo goals'
// evaluations (1016 -> 870) and cost 7% on the 76 posed census meshes (5571 -> 5984), with every
// status the same; a default tuned on the demos alone would have been slower where it matters.
//
// usage: bench/optim/solver_settings.sh DIR [--goal G] [--outer] [--fill-density R] SETTING...
//   DIR: meshes (.ply .obj .stl .off .3mf), each posed as it is to be printed; e.g. the census's
//        (tar -xJf ../shared/realposed/meshes.tar.xz -C DIR)
//   SETTING: name=value[,name=value...], names initial_inner_tolerance, initial_penalty, memory,
//            stationarity_tolerance (the solver's AlOptions, optim/augmented_lagrangian.h) and
//            warm_penalty_cap (OptimizeOptions: the first penalty of a repair or correction round)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "meshio/load_input.h"
#include "optimize/offset_optimization.h"

using namespace offsetopt;

namespace {

struct Setting {
  std::string text;  // as given ("default" for none)
  AlOptions solver;
  double warm_penalty_cap = OptimizeOptions::defaults().warm_penalty_cap;  // a later round's first penalty at most
};

// Applies "name=value[,name=value...]" to the defaults; false on an unknown name or a bad value.
bool parse_setting(const std::string& text, Setting& out) {
  out.text = text;
  out.solver = OptimizeOptions::default_solver_params();
  std::stringstream parts(text);
  std::string part;
  while (std::getline(parts, part, ',')) {
    const std::size_t eq = part.find('=');
    if (eq == std::string::npos) return false;
    const std::string name = part.substr(0, eq);
    char* end = nullptr;
    const double value = std::strtod(part.c_str() + eq + 1, &end);
    if (end == part.c_str() + eq + 1 || *end != '\0' || !std::isfinite(value)) return false;
    if (name == "initial_inner_tolerance") out.solver.initial_inner_tolerance = value;
    else if (name == "initial_penalty") out.solver.initial_penalty = value;
    else if (name == "stationarity_tolerance") out.solver.stationarity_tolerance = value;
    else if (name == "memory") out.solver.inner.memory = static_cast<int>(value);
    else if (name == "warm_penalty_cap") out.warm_penalty_cap = value;
    else return false;
  }
  return true;
}

struct Tally {
  long long evaluations = 0;
  int verified = 0, runs = 0;
  double seconds = 0.0;
  std::vector<double> objectives;  // per mesh, NaN when the run did not get as far as a solve
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: solver_settings DIR [--goal G] [--outer] [--fill-density R] SETTING...\n");
    return 2;
  }
  OptimizeOptions base = OptimizeOptions::defaults();
  base.output_precision = StoredPrecision::float32;
  std::vector<Setting> settings(1);
  settings[0].text = "default";
  settings[0].solver = base.solver;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--goal" && i + 1 < argc) {
      const std::string g = argv[++i];
      if (g == "stand") base.goal = GoalKind::stand;
      else if (g == "stand-filled") base.goal = GoalKind::stand_filled;
      else if (g == "roly-poly") base.goal = GoalKind::roly_poly;
      else {
        std::fprintf(stderr, "Error: goal '%s' is not one this benchmark sets up (stand, stand-filled, roly-poly)\n", g.c_str());
        return 2;
      }
    } else if (arg == "--outer") {
      base.outer = true;
    } else if (arg == "--fill-density" && i + 1 < argc) {
      base.fill_density = std::atof(argv[++i]);
    } else {
      Setting s;
      if (!parse_setting(arg, s)) {
        std::fprintf(stderr, "Error: setting '%s' is not name=value[,name=value...] with a known name\n", arg.c_str());
        return 2;
      }
      settings.push_back(s);
    }
  }
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(argv[1])) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".ply" || ext == ".obj" || ext == ".stl" || ext == ".off" || ext == ".3mf") paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());  // the same order on every machine
  if (paths.empty()) {
    std::fprintf(stderr, "Error: no mesh in %s\n", argv[1]);
    return 2;
  }

  std::vector<Tally> tallies(settings.size());
  std::vector<std::string> skipped;
  for (const std::string& path : paths) {
    InputMesh loaded;
    try {
      loaded = load_input(path);
    } catch (const MeshInputError& e) {
      skipped.push_back(path + ": " + e.what());
      continue;
    }
    for (std::size_t s = 0; s < settings.size(); ++s) {
      OptimizeOptions options = base;
      options.solver = settings[s].solver;
      options.warm_penalty_cap = settings[s].warm_penalty_cap;
      options.input_self_intersections = loaded.self_intersections;
      const auto start = std::chrono::steady_clock::now();
      const OptimizeResult r = optimize_offsets(loaded.mesh, options);
      Tally& t = tallies[s];
      t.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++t.runs;
      t.evaluations += r.solver.evaluations;
      if (r.status == OptimizeStatus::verified) ++t.verified;
      t.objectives.push_back(r.status == OptimizeStatus::bad_input ? std::nan("") : r.solver.objective);
    }
  }
  for (const std::string& line : skipped) std::fprintf(stderr, "Warning: skipped %s\n", line.c_str());
  std::printf("%zu meshes from %s\n", paths.size() - skipped.size(), argv[1]);
  std::printf("%-48s %12s %9s %14s %10s\n", "setting", "evaluations", "verified", "max |d obj|", "seconds");
  for (std::size_t s = 0; s < settings.size(); ++s) {
    const Tally& t = tallies[s];
    double moved = 0.0;  // the largest relative change of the objective against the defaults
    for (std::size_t m = 0; m < t.objectives.size(); ++m) {
      const double a = tallies[0].objectives[m], b = t.objectives[m];
      if (std::isfinite(a) && std::isfinite(b)) moved = std::max(moved, std::abs(b - a) / std::max(1e-12, std::abs(a)));
    }
    std::printf("%-48s %12lld %4d/%-4d %14.2e %10.2f\n", settings[s].text.c_str(), t.evaluations, t.verified, t.runs, moved, t.seconds);
  }
  return 0;
}
