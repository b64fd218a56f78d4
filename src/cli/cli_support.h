// Shared pieces of the command-line layer: option-value parsing with ranges, the usage-error
// exception every command maps to exit code 2, and writing a result to a file or stdout.
#pragma once
#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cli/commands.h"
#include "io/json.h"
#include "meshio/load_input.h"
#include "util/seconds_since.h"

namespace offsetopt::cli {

// A point or vector as the reports write it: [x, y, z].
inline Json vec3(const Eigen::Vector3d& v) { return Json::array_of({v.x(), v.y(), v.z()}); }

// A usage or bad-input problem found by the CLI layer: printed as "Error: <what>", exit 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Walks an argument list: positional arguments and "--name value" options.
class ArgCursor {
 public:
  explicit ArgCursor(const Args& args) : args_(args) {}
  bool done() const { return index_ >= args_.size(); }
  const std::string& next() { return args_[index_++]; }
  // The value following option `name`; UsageError when it is missing.
  const std::string& value_of(const std::string& name);

 private:
  const Args& args_;
  std::size_t index_ = 0;
};

// Strict number parsing: the whole text must be a finite number within [lo, hi].
double parse_double(const std::string& text, const std::string& option, double lo, double hi);
int parse_int(const std::string& text, const std::string& option, int lo, int hi);

// Writes `text` to `path`, or to stdout when path is "-". Refuses (UsageError) to overwrite any
// of `inputs` so a user's mesh is never clobbered by a mistyped output name.
void write_text(const std::string& path, const std::string& text, const std::vector<std::string>& inputs = {});

// Same protection for mesh outputs: UsageError when `output` names one of `inputs`.
void refuse_overwriting_input(const std::string& output, const std::vector<std::string>& inputs);

// The values an option takes, as its table row states them: the help prints this and the
// parser checks this (read_real, read_integer), so the two cannot disagree. A number range is
// [lo, hi] (lo excluded when lo_open); when the upper bound depends on the input (hi_words:
// "#vertices - 1"), the help names it and the command checks it once the input is read, the
// parser only lo. Other options give their values in words ("mass | laplacian", "flag").
struct OptionRange {
  enum class Kind { words, real, integer };
  Kind kind = Kind::words;
  const char* words = "";     // words: the whole range text; numbers: text after "[lo, hi]" (" mesh units")
  double lo = 0.0, hi = 0.0;
  bool lo_open = false;
  const char* hi_words = "";  // printed in place of hi, which is then not checked by the parser

  constexpr OptionRange(const char* text) : words(text) {}  // NOLINT: rows name word ranges as plain strings
  static constexpr OptionRange real(double lo, double hi, const char* after = "") {
    return OptionRange(Kind::real, lo, hi, false, "", after);
  }
  // (lo, hi]: lo itself refused.
  static constexpr OptionRange real_above(double lo, double hi, const char* after = "") {
    return OptionRange(Kind::real, lo, hi, true, "", after);
  }
  static constexpr OptionRange integer(int lo, int hi, const char* after = "") {
    return OptionRange(Kind::integer, lo, hi, false, "", after);
  }
  // [lo, hi_words]: the upper bound is the input's, checked by the command.
  static constexpr OptionRange integer_up_to(int lo, const char* hi_words) {
    return OptionRange(Kind::integer, lo, 2147483647.0, false, hi_words, "");
  }

 private:
  constexpr OptionRange(Kind k, double l, double h, bool open, const char* hw, const char* after)
      : kind(k), words(after), lo(l), hi(h), lo_open(open), hi_words(hw) {}
};

// The range as the help prints it: "[0, 1e12] mesh units", "(0, 1e12]", "[1, #vertices - 1]".
std::string range_text(const OptionRange& range);

// One row of a command's option table: the single place an option is declared. The help text is
// generated from the table, and each parser refuses anything not in it (require_known_option),
// so every accepted option is in the help; tests/cli/test_help_agreement.cpp runs every row's
// example through the real parser, so every option in the help is accepted, and a value just
// outside every number range is refused.
struct OptionSpec {
  const char* names;          // "--wall" or "-o, --output"
  const char* argument;       // "T", "FILE", ...; "" for a flag
  const char* default_value;  // "0.01 diag", "none", "off"
  OptionRange range;          // OptionRange::real(0, 1e12), "mass | laplacian", "flag"
  const char* help;           // one sentence or two; wrapped by the generator
  const char* example;        // a value the parser accepts ("" for a flag)
};

// `text`, the value of option `arg`, parsed and checked against the range of arg's row in
// `options`: UsageError "--wall must be in [0, 1e12], got -1" when outside.
double parse_real_option(const std::vector<OptionSpec>& options, const std::string& arg, const std::string& text);
int parse_integer_option(const std::vector<OptionSpec>& options, const std::string& arg, const std::string& text);
// `text` parsed as a number in `range` (a real or integer one), for option `option`.
double parse_in_range(const std::string& text, const std::string& option, const OptionRange& range);

struct CommandHelp {
  const char* intro;   // usage lines and what the command does (ends with a newline)
  std::vector<OptionSpec> options;
  const char* outro;   // exit codes, notes (may be empty)
};

// The help text: intro, "options (default; range):" with each row, outro.
std::string format_help(const CommandHelp& help);

// UsageError for an argument that looks like an option ("-x", "--name"; not "-" alone) and is
// not one of `options`' names.
void require_known_option(const char* command, const std::vector<OptionSpec>& options, const std::string& arg);

// The words of `text` between any of the characters of `separators` (empty words dropped).
std::vector<std::string> split_words(const std::string& text, const char* separators);
// The names of an option table row: "-o, --output" -> {"-o", "--output"}.
std::vector<std::string> option_names(const char* names);

// The value of --unit: one of the 3MF units (meshio/write_3mf.h), else UsageError.
std::string parse_unit(const std::string& text);

// Prints each warning as "Warning: <text>" on stderr unless quiet.
void print_warnings(const std::vector<std::string>& warnings, bool quiet = false);

}  // namespace offsetopt::cli
