// Issue 14: `--help` of every command lists every option with its default and range, and the
// help and the parser agree. Each option block of the real binary's help is parsed from the
// text; every name (and alias) is run through the parser with the block's example value,
// followed by --help, which must then print the same help (the option was accepted); the
// parser's own comparisons (`arg == "--name"` in src/cli/cmd_<command>.cpp) must all be names
// the help lists; and a name the help does not list is refused with exit 2.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "../meshio/meshio_test_util.h"

using namespace meshio_test;

namespace {

struct HelpOption {
  std::vector<std::string> names;
  std::string argument, block;
  std::string example() const {
    const std::size_t at = block.find("example: ");
    if (at == std::string::npos) return "";
    std::size_t end = at + 9;
    while (end < block.size() && block[end] != ' ' && block[end] != '\n') ++end;
    return block.substr(at + 9, end - at - 9);
  }
};

// Option blocks: a line "  -x, --name ARG  help..." and the deeper-indented lines after it.
std::vector<HelpOption> parse_help(const std::string& help) {
  std::vector<HelpOption> options;
  bool in_options = false;
  for (const std::string& line : lines_of(help)) {
    if (line == "options:") {
      in_options = true;
      continue;
    }
    if (!in_options) continue;
    if (line.size() > 3 && line.compare(0, 3, "  -") == 0) {
      const std::size_t gap = line.find("  ", 2);
      const std::string head = line.substr(2, gap == std::string::npos ? std::string::npos : gap - 2);
      HelpOption o;
      std::string rest = head;
      for (;;) {
        const std::size_t comma = rest.find(", ");
        if (comma == std::string::npos) break;
        o.names.push_back(rest.substr(0, comma));
        rest = rest.substr(comma + 2);
      }
      const std::size_t space = rest.find(' ');
      o.names.push_back(rest.substr(0, space));
      if (space != std::string::npos) o.argument = rest.substr(space + 1);
      o.block = line + "\n";
      options.push_back(o);
    } else if (!options.empty() && line.size() > 4 && line.compare(0, 4, "    ") == 0) {
      options.back().block += line + "\n";
    } else {
      in_options = line.empty() ? false : in_options;
    }
  }
  return options;
}

// The option names the parser compares arguments with: every `arg == "-..."` in the source.
std::set<std::string> parser_names(const std::string& command) {
  const std::string source = read_file(std::string(OFFSETOPT_SOURCE_DIR) + "/src/cli/cmd_" + command + ".cpp");
  std::set<std::string> names;
  const std::string needle = "arg == \"";
  for (std::size_t at = source.find(needle); at != std::string::npos; at = source.find(needle, at + 1)) {
    const std::size_t start = at + needle.size();
    const std::size_t end = source.find('"', start);
    const std::string name = source.substr(start, end - start);
    if (name.size() > 1 && name[0] == '-') names.insert(name);
  }
  return names;
}

const char* const kCommands[] = {"check", "inspect", "basis", "skeleton", "optimize", "generate", "batch", "preview"};

}  // namespace

TEST_CASE("help and parser agree for every command, and every option states its default and range") {
  TempDir dir;
  for (const std::string command : kCommands) {
    CAPTURE(command);
    const RunResult help = run_offsetopt(command + " --help", dir);
    REQUIRE(help.exit_code == 0);
    const std::vector<HelpOption> options = parse_help(help.out);
    REQUIRE(options.size() >= 2);
    std::set<std::string> listed;
    for (const HelpOption& o : options) {
      CAPTURE(o.block);
      CHECK(o.block.find("default:") != std::string::npos);
      CHECK(o.block.find("range:") != std::string::npos);
      CHECK(o.argument.empty() == o.example().empty());  // a value to try for every option that takes one
      for (const std::string& name : o.names) {
        listed.insert(name);
        CAPTURE(name);
        const std::string value = o.argument.empty() ? "" : " " + shell_quote(o.example());
        const RunResult r = run_offsetopt(command + " " + name + value + " --help", dir);
        CHECK(r.exit_code == 0);
        CHECK(r.err == "");
        if (name != "--list") CHECK(r.out == help.out);  // --help was reached: the option and its value were accepted
      }
    }
    for (const std::string& name : parser_names(command)) {
      CAPTURE(name);
      CHECK(listed.count(name) == 1);
    }
    const RunResult unknown = run_offsetopt(command + " --no-such-option --help", dir);
    CHECK(unknown.exit_code == 2);
    CHECK(unknown.err.find("unknown option '--no-such-option'") != std::string::npos);
  }
}

TEST_CASE("help: a value outside an option's stated range is refused with exit 2") {
  TempDir dir;
  const RunResult wall = run_offsetopt("optimize --wall -1 --help", dir);
  CHECK(wall.exit_code == 2);
  CHECK(wall.err.find("--wall must be in [0,") != std::string::npos);
  const RunResult unit = run_offsetopt("optimize --unit furlong --help", dir);
  CHECK(unit.exit_code == 2);
  CHECK(unit.err.find("--unit must be one of micron, millimeter") != std::string::npos);
  const RunResult jobs = run_offsetopt("batch --jobs 0 --help", dir);
  CHECK(jobs.exit_code == 2);
}

namespace {

// The block's "range: ..." text, its wrapped lines joined with single spaces.
std::string range_of(const HelpOption& o) {
  std::string flat;
  for (const char c : o.block) {
    const char d = c == '\n' ? ' ' : c;
    if (d == ' ' && !flat.empty() && flat.back() == ' ') continue;
    flat += d;
  }
  const std::size_t at = flat.find("; range: ");
  if (at == std::string::npos) return "";
  const std::size_t start = at + 9;
  const std::size_t end = flat.find("; example:", start);
  std::string range = flat.substr(start, end == std::string::npos ? std::string::npos : end - start);
  while (!range.empty() && range.back() == ' ') range.pop_back();
  return range;
}

std::string number_text(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

// `x` moved by one part in 10^9 towards `direction` (strtod refuses subnormals, so not nextafter).
double nudged(double x, int direction) { return x + direction * (x == 0.0 ? 1e-9 : std::fabs(x) * 1e-9); }

bool is_number(const std::string& text, double& value) {
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

// Refused the way usage errors are: exit 2, nothing on stdout, one "Error: ..." line on stderr.
void check_refused(const RunResult& r) {
  CHECK(r.exit_code == 2);
  CHECK(r.out == "");
  CHECK(r.err.rfind("Error: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}

// A number outside the help's `interval` is refused, and the message states that interval (or
// that the option takes integers).
void check_outside(const RunResult& r, const std::string& interval) {
  CAPTURE(r.err);
  check_refused(r);
  CHECK((r.err.find(" must be in " + interval + ", got ") != std::string::npos ||
         r.err.find(" expects an integer, got ") != std::string::npos));
}

}  // namespace

TEST_CASE("help: each number range's bounds are accepted, a value just outside is refused with one Error line naming the "
          "help's range, and each listed word is accepted") {
  TempDir dir;
  int number_ranges = 0, word_ranges = 0;
  for (const std::string command : kCommands) {
    const RunResult help = run_offsetopt(command + " --help", dir);
    REQUIRE(help.exit_code == 0);
    for (const HelpOption& o : parse_help(help.out)) {
      if (o.argument.empty()) continue;
      const std::string range = range_of(o), name = o.names.back();
      CAPTURE(command);
      CAPTURE(name);
      CAPTURE(range);
      auto run = [&](const std::string& value) { return run_offsetopt(command + " " + name + " " + shell_quote(value) + " --help", dir); };
      if (!range.empty() && (range[0] == '[' || range[0] == '(')) {
        // "[lo, hi] words" or "(lo, hi]" or "[lo, words for an upper bound the input sets]".
        ++number_ranges;
        const std::size_t comma = range.find(", "), close = range.find(']');
        REQUIRE(comma != std::string::npos);
        REQUIRE(close != std::string::npos);
        const std::string interval = range.substr(0, close + 1);
        double lo = 0, hi = 0;
        REQUIRE(is_number(range.substr(1, comma - 1), lo));
        const bool hi_known = is_number(range.substr(comma + 2, close - comma - 2), hi);
        const bool lo_open = range[0] == '(';
        const double below = lo_open ? lo : nudged(lo, -1);
        // Just below, and the integer below (an integer option refuses a fraction as such).
        for (const double outside : {below, std::floor(below)}) check_outside(run(number_text(outside)), interval);
        CHECK(run(number_text(lo_open ? nudged(lo, 1) : lo)).exit_code == 0);
        if (hi_known) {
          CHECK(run(number_text(hi)).exit_code == 0);
          for (const double outside : {nudged(hi, 1), std::floor(hi) + 1})
            if (outside > hi) check_outside(run(number_text(outside)), interval);
        }
      } else if (range.find(" | ") != std::string::npos) {
        ++word_ranges;
        std::string rest = range;
        for (std::size_t bar; (bar = rest.find(" | ")) != std::string::npos || !rest.empty();) {
          const std::string word = rest.substr(0, bar);
          rest = bar == std::string::npos ? "" : rest.substr(bar + 3);
          CAPTURE(word);
          CHECK(run(word).exit_code == 0);
        }
        check_refused(run("no-such-value"));
      }
    }
  }
  CHECK(number_ranges >= 20);
  CHECK(word_ranges >= 8);
}
