// `offsetopt batch` (issue 14): a manifest of small demo goals runs in parallel; a second run
// skips every line; the summary counts what happened; every output is byte-identical to a single
// `optimize` run with the same arguments; --line and --shard select lines; a bad manifest is
// refused naming its line.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "../meshio/meshio_test_util.h"
#include "io/json.h"

using namespace meshio_test;

namespace {

// Runs the binary in `folder` (batch resolves the manifest's paths there too).
RunResult run_in(const std::string& folder, const std::string& arguments) {
  const std::string out_path = folder + "/.stdout", err_path = folder + "/.stderr";
  const std::string command = "cd " + shell_quote(folder) + " && timeout 300 " + shell_quote(OFFSETOPT_BINARY) + " " +
                              arguments + " >" + shell_quote(out_path) + " 2>" + shell_quote(err_path);
  const int status = std::system(command.c_str());
  RunResult r;
  r.exit_code = offsetopt::test::exit_code_of(status);
  r.out = read_file(out_path);
  r.err = read_file(err_path);
  return r;
}

struct Line {
  const char* mesh;
  const char* goal;
  const char* options;
  const char* output;  // "" for the default prefix
  int exit_code;
};

// Small demo goals (0.1-0.3 s each), one that ends with exit 3, and a 3MF-writing run.
const Line kLines[] = {
    {"in/top-coarse.obj", "spin", "--no-timings --threads 1", "", 0},
    {"in/sphere.obj", "volume", "--target-volume 20000 --no-timings", "out/sphere", 0},
    {"in/buoy.obj", "float", "--fluid-density 0.806 --no-timings --threads 1", "", 0},
    {"in/capsule.obj", "spin", "--k 2 --no-timings --threads 1", "", 3},
};

std::string prefix_of(const Line& line) {
  if (*line.output) return line.output;
  const std::filesystem::path p(line.mesh);
  return (p.parent_path() / p.stem()).string() + "." + line.goal;
}

}  // namespace

TEST_CASE("batch: parallel, resumable, summary counts right, outputs byte-identical to single runs") {
  TempDir dir;
  const std::string folder = dir.path();
  std::filesystem::create_directories(folder + "/in");
  for (const char* name : {"top-coarse", "sphere", "buoy", "capsule"})
    REQUIRE(run_in(folder, std::string("generate ") + name + " -o in/" + name + ".obj").exit_code == 0);
  std::string manifest = "input\tgoal\toptions\toutput\n# a comment line\n";
  for (const Line& line : kLines)
    manifest += std::string(line.mesh) + "\t" + line.goal + "\t" + line.options + "\t" + line.output + "\n";
  write_file(folder + "/farm.tsv", manifest);

  const RunResult first = run_in(folder, "batch farm.tsv --jobs 2 --format 3mf");
  CAPTURE(first.err);
  CHECK(first.exit_code == 3);  // one line ends with 3, none worse
  offsetopt::Json summary = offsetopt::Json::parse(read_file(folder + "/farm.summary.json"));
  CHECK(summary["lines"].as_number() == 4);
  CHECK(summary["ran"].as_number() == 4);
  CHECK(summary["skipped"].as_number() == 0);
  CHECK(summary["exit_counts"]["0"].as_number() == 3);
  CHECK(summary["exit_counts"]["3"].as_number() == 1);
  const std::vector<std::string> tsv = lines_of(read_file(folder + "/farm.summary.tsv"));
  REQUIRE(tsv.size() == 5);
  CHECK(tsv[0] == "line\tinput\tgoal\toutput\tstatus\texit\treason\tseconds");
  CHECK(tsv[4].find("4\tin/capsule.obj\tspin\tin/capsule.spin\tran\t3\t") == 0);
  CHECK(tsv[4].find("goal not met") != std::string::npos);
  // Progress per job on stderr.
  for (const Line& line : kLines) CHECK(first.err.find(std::string(line.mesh) + " " + line.goal + ": exit ") != std::string::npos);

  std::vector<std::string> solids, reports;
  for (const Line& line : kLines) {
    const std::string prefix = folder + "/" + prefix_of(line);
    solids.push_back(read_file(prefix + ".3mf"));
    reports.push_back(read_file(prefix + ".json"));
    CHECK(solids.back().size() > 1000);
    CHECK(std::filesystem::exists(prefix + ".log"));
    CHECK(std::filesystem::exists(prefix + ".key"));
  }

  // The second run skips every line, and reports the earlier exit codes.
  const RunResult second = run_in(folder, "batch farm.tsv --jobs 2 --format 3mf");
  CAPTURE(second.err);
  CHECK(second.exit_code == 3);
  offsetopt::Json again = offsetopt::Json::parse(read_file(folder + "/farm.summary.json"));
  CHECK(again["ran"].as_number() == 0);
  CHECK(again["skipped"].as_number() == 4);
  CHECK(again["exit_counts"]["0"].as_number() == 3);
  CHECK(again["exit_counts"]["3"].as_number() == 1);
  CHECK(second.err.find("skipped") != std::string::npos);

  // Single runs with the same arguments write the same bytes.
  for (std::size_t i = 0; i < std::size(kLines); ++i) {
    const Line& line = kLines[i];
    CAPTURE(line.mesh);
    const std::string prefix = prefix_of(line);
    std::filesystem::remove(folder + "/" + prefix + ".3mf");
    std::filesystem::remove(folder + "/" + prefix + ".json");
    const RunResult single = run_in(folder, std::string("optimize ") + line.mesh + " --goal " + line.goal + " -o " + prefix +
                                                ".3mf --report " + prefix + ".json " + line.options);
    CHECK(single.exit_code == line.exit_code);
    CHECK(read_file(folder + "/" + prefix + ".3mf") == solids[i]);
    CHECK(read_file(folder + "/" + prefix + ".json") == reports[i]);
  }

  // A changed input is run again; the others stay skipped.
  REQUIRE(run_in(folder, "generate sphere -o in/sphere.obj").exit_code == 0);  // same bytes: still skipped
  write_file(folder + "/in/buoy.obj", read_file(folder + "/in/buoy.obj") + "# changed\n");
  const RunResult third = run_in(folder, "batch farm.tsv --format 3mf --quiet");
  CHECK(third.err.empty());
  offsetopt::Json after_change = offsetopt::Json::parse(read_file(folder + "/farm.summary.json"));
  CHECK(after_change["ran"].as_number() == 1);
  CHECK(after_change["skipped"].as_number() == 3);

  // One line, one shard (what a Slurm array task or a Kubernetes indexed pod runs).
  const RunResult one = run_in(folder, "batch farm.tsv --format 3mf --line 2");
  CHECK(one.exit_code == 0);
  const std::vector<std::string> line_tsv = lines_of(read_file(folder + "/farm.summary.line-2.tsv"));
  REQUIRE(line_tsv.size() == 2);
  CHECK(line_tsv[1].find("2\tin/sphere.obj\tvolume\tout/sphere\tskipped\t0\t") == 0);
  const RunResult shard = run_in(folder, "batch farm.tsv --format 3mf --shard 1/2");
  CHECK(shard.exit_code == 3);  // lines 2 and 4
  const std::vector<std::string> shard_tsv = lines_of(read_file(folder + "/farm.summary.shard-1-of-2.tsv"));
  REQUIRE(shard_tsv.size() == 3);
  CHECK(shard_tsv[1].find("2\t") == 0);
  CHECK(shard_tsv[2].find("4\t") == 0);
}

TEST_CASE("batch: a bad manifest is refused with exit 2 naming the file and line, a failing line is retried") {
  TempDir dir;
  const std::string folder = dir.path();
  write_file(folder + "/bad.tsv", "input\tgoal\toptions\nx.obj\tstand\t--wal 3\n");
  RunResult r = run_in(folder, "batch bad.tsv");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("Error: bad.tsv:2: unknown optimize option '--wal'") != std::string::npos);
  write_file(folder + "/bad.tsv", "input\tgoal\toptions\nx.obj\tstand\t-o y.obj\n");
  r = run_in(folder, "batch bad.tsv");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("bad.tsv:2: options may not contain -o") != std::string::npos);
  write_file(folder + "/bad.tsv", "input\tgoal\nx.obj\tstand\nx.obj\tstand\n");
  r = run_in(folder, "batch bad.tsv");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("bad.tsv:3: output prefix 'x.stand' is also line 2's") != std::string::npos);
  write_file(folder + "/bad.tsv", "file\tgoal\nx.obj\tstand\n");
  r = run_in(folder, "batch bad.tsv");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("bad.tsv:1: unknown manifest column 'file'") != std::string::npos);

  // A missing input: the line ends with exit 2 and its reason, and is not recorded as done.
  write_file(folder + "/missing.tsv", "input\tgoal\nnone.obj\tstand\n");
  for (int run = 0; run < 2; ++run) {
    r = run_in(folder, "batch missing.tsv --quiet");
    CHECK(r.exit_code == 2);
    const std::vector<std::string> tsv = lines_of(read_file(folder + "/missing.summary.tsv"));
    REQUIRE(tsv.size() == 2);
    CHECK(tsv[1].find("1\tnone.obj\tstand\tnone.stand\tran\t2\tnone.obj: cannot open file") == 0);
  }
}
