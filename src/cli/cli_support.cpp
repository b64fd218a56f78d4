#include "cli/cli_support.h"

#include "meshio/write_3mf.h"
#include "util/format_double.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace offsetopt::cli {

namespace {

// A bound as people write it: "1e12", "1e-6", "0.999999" (to_chars' "1e+12", "1e-06" tidied).
std::string bound_text(double value) {
  std::string text = format_double(value);
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = exponent[0] == '-';
  if (exponent[0] == '-' || exponent[0] == '+') exponent.erase(0, 1);
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

}  // namespace

const std::string& ArgCursor::value_of(const std::string& name) {
  if (done()) throw UsageError("option " + name + " needs a value");
  return next();
}

namespace {

const OptionSpec& row_of(const std::vector<OptionSpec>& options, const std::string& arg) {
  for (const OptionSpec& o : options)
    for (const std::string& name : option_names(o.names))
      if (name == arg) return o;
  throw std::logic_error("option " + arg + " has no row in its command's table");
}

// "[0, 1e12]", "(0, 1e12]", "[1, #vertices - 1]": a number range without the words after it.
std::string interval_text(const OptionRange& range) {
  auto text = [&range](double bound) {
    return range.kind == OptionRange::Kind::integer ? std::to_string(static_cast<long long>(bound)) : bound_text(bound);
  };
  return std::string(range.lo_open ? "(" : "[") + text(range.lo) + ", " +
         (*range.hi_words ? std::string(range.hi_words) : text(range.hi)) + "]";
}

}  // namespace

std::string range_text(const OptionRange& range) {
  return range.kind == OptionRange::Kind::words ? range.words : interval_text(range) + range.words;
}

double parse_in_range(const std::string& text, const std::string& option, const OptionRange& range) {
  const bool integer = range.kind == OptionRange::Kind::integer;
  char* end = nullptr;
  errno = 0;
  const double value = integer ? static_cast<double>(std::strtol(text.c_str(), &end, 10)) : std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
    throw UsageError(option + (integer ? " expects an integer, got '" : " expects a number, got '") + text + "'");
  const bool below = range.lo_open ? !(value > range.lo) : value < range.lo;
  if (below || value > range.hi) throw UsageError(option + " must be in " + interval_text(range) + ", got " + text);
  return value;
}

double parse_real_option(const std::vector<OptionSpec>& options, const std::string& arg, const std::string& text) {
  const OptionSpec& row = row_of(options, arg);
  if (row.range.kind != OptionRange::Kind::real) throw std::logic_error(arg + "'s row is not a real range");
  return parse_in_range(text, arg, row.range);
}

double parse_double(const std::string& text, const std::string& option, double lo, double hi) {
  return parse_in_range(text, option, OptionRange::real(lo, hi));
}

int parse_int(const std::string& text, const std::string& option, int lo, int hi) {
  return static_cast<int>(parse_in_range(text, option, OptionRange::integer(lo, hi)));
}

int parse_integer_option(const std::vector<OptionSpec>& options, const std::string& arg, const std::string& text) {
  const OptionSpec& row = row_of(options, arg);
  if (row.range.kind != OptionRange::Kind::integer) throw std::logic_error(arg + "'s row is not an integer range");
  return static_cast<int>(parse_in_range(text, arg, row.range));
}

namespace {

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return a == b;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

}  // namespace

void refuse_overwriting_input(const std::string& output, const std::vector<std::string>& inputs) {
  for (const auto& input : inputs)
    if (output != "-" && same_file(output, input))
      throw UsageError("output " + output + " is the input file; refusing to overwrite it");
}

void write_text(const std::string& path, const std::string& text, const std::vector<std::string>& inputs) {
  if (path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
    return;
  }
  refuse_overwriting_input(path, inputs);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw UsageError("cannot open " + path + " for writing");
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) throw UsageError("writing " + path + " failed");
}

namespace {


// Appends `text` wrapped at 96 columns, every line indented by `indent` (the first line's
// indentation is already written when `first_written`).
void append_wrapped(std::string& out, const std::string& text, std::size_t indent, bool first_written) {
  const std::size_t width = 96;
  std::size_t column = first_written ? indent : 0;
  if (!first_written) {
    out.append(indent, ' ');
    column = indent;
  }
  std::size_t start = 0;
  bool line_empty = true;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!line_empty && column + 1 + word.size() > width) {
      out += '\n';
      out.append(indent, ' ');
      column = indent;
      line_empty = true;
    }
    if (!line_empty) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
    line_empty = false;
    start = end + 1;
  }
  out += '\n';
}

}  // namespace

std::string format_help(const CommandHelp& help) {
  std::string out = help.intro;
  out += "\noptions:\n";
  const std::size_t indent = 26;
  for (const OptionSpec& o : help.options) {
    std::string head = std::string("  ") + o.names;
    if (*o.argument) head += std::string(" ") + o.argument;
    out += head;
    if (head.size() + 1 < indent) {
      out.append(indent - head.size(), ' ');
      append_wrapped(out, o.help, indent, true);
    } else {
      out += '\n';
      append_wrapped(out, o.help, indent, false);
    }
    std::string facts = std::string("default: ") + o.default_value + "; range: " + range_text(o.range);
    // "example: X" stays on one line (a placeholder for its space survives the wrapping).
    if (*o.example) facts += std::string("; example:\x01") + o.example;
    const std::size_t start = out.size();
    append_wrapped(out, facts, indent, false);
    for (std::size_t i = start; i < out.size(); ++i)
      if (out[i] == '\x01') out[i] = ' ';
  }
  if (*help.outro) {
    out += "\n";
    out += help.outro;
  }
  return out;
}

void require_known_option(const char* command, const std::vector<OptionSpec>& options, const std::string& arg) {
  if (arg.size() < 2 || arg[0] != '-') return;
  for (const OptionSpec& o : options)
    for (const std::string& name : option_names(o.names))
      if (name == arg) return;
  throw UsageError(std::string("unknown option '") + arg + "' for " + command + " (try 'offsetopt " + command + " --help')");
}

std::string parse_unit(const std::string& text) {
  if (is_unit_3mf(text)) return text;
  std::string list;
  for (const std::string& u : units_3mf()) list += (list.empty() ? "" : ", ") + u;
  throw UsageError("--unit must be one of " + list + ", got '" + text + "'");
}

void print_warnings(const std::vector<std::string>& warnings, bool quiet) {
  if (quiet) return;
  for (const auto& w : warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
}

}  // namespace offsetopt::cli

namespace offsetopt::cli {

std::vector<std::string> split_words(const std::string& text, const char* separators) {
  std::vector<std::string> out;
  std::string current;
  for (const char c : text) {
    if (std::strchr(separators, c) != nullptr) {
      if (!current.empty()) out.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) out.push_back(current);
  return out;
}

std::vector<std::string> option_names(const char* names) { return split_words(names, ", "); }

}  // namespace offsetopt::cli
