// The live progress line (cli/progress_line.h): drawn in place once the run has lasted its delay,
// the stages in the order they started with their percentages, finished stages removed, cleared
// before a normal line; nothing at all when disabled (stderr not a terminal) or before the delay.
#include <doctest/doctest.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "../temp_dir.h"
#include "cli/progress_line.h"

using offsetopt::cli::ProgressLine;

namespace {

// Runs `body` with stderr sent to a file and returns what it wrote.
template <typename Body>
std::string captured_stderr(Body body) {
  static const TempDir dir("offsetopt-progress");
  const std::string path = dir.path() + "/stderr.txt";
  std::fflush(stderr);
  const int saved = dup(fileno(stderr));
  REQUIRE(std::freopen(path.c_str(), "w", stderr) != nullptr);
  body();
  std::fflush(stderr);
  REQUIRE(dup2(saved, fileno(stderr)) >= 0);
  close(saved);
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("the progress line: stages and percentages in place, removed when done, cleared for a normal line") {
  const auto long_ago = std::chrono::steady_clock::now() - std::chrono::seconds(10);
  const std::string out = captured_stderr([&] {
    ProgressLine line(true, long_ago);
    line.update("basis", 0.25);
    line.print_line("skeleton: contracting");
    line.update("skeleton", 0.5);  // drawn: the line was cleared, so nothing throttles it
    line.update("basis", 1.0);
  });
  CHECK(out.find("\r\033[K  basis 25%  (") == 0);
  const std::size_t normal = out.find("\r\033[Kskeleton: contracting\n");
  REQUIRE(normal != std::string::npos);
  CHECK(out.find("basis 25% · skeleton 50%", normal) != std::string::npos);
  // The destructor erases the line it left.
  CHECK(out.size() >= 4);
  CHECK(out.substr(out.size() - 4) == "\r\033[K");
}

TEST_CASE("the progress line draws nothing when disabled or before its delay") {
  const auto now = std::chrono::steady_clock::now();
  const std::string out = captured_stderr([&] {
    ProgressLine off(false, now - std::chrono::seconds(10));
    off.update("basis", 0.5);
    ProgressLine early(true, now, 60.0);
    early.update("basis", 0.5);
    early.print_line("a normal line");
  });
  CHECK(out == "a normal line\n");
}
