#include "meshio/read_off.h"

#include "meshio/load_mesh.h"
#include "meshio/read_text.h"

namespace offsetopt {

namespace {

[[noreturn]] void fail(const std::string& name, int line, const std::string& what) {
  throw MeshInputError(name + ":" + std::to_string(line) + ": " + what);
}

// Next line with content, comments removed, split into tokens. False at the end of the text.
bool next_tokens(LineScanner& lines, std::vector<std::string_view>& tokens) {
  std::string_view line;
  while (lines.next(line)) {
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    split_tokens(line, tokens, true);
    if (!tokens.empty()) return true;
  }
  return false;
}

std::int64_t parse_count(const std::string& name, int line, std::string_view token, const char* what) {
  std::int64_t value = 0;
  bool overflow = false;
  if (!parse_integer(token, value, overflow) || value < 0)
    fail(name, line, std::string(what) + " '" + quote_bytes(token) + "' is not a non-negative integer");
  if (overflow) fail(name, line, std::string(what) + " '" + quote_bytes(token) + "' is too large");
  return value;
}

}  // namespace

RawMesh read_off(const std::string& name, const std::string& text) {
  {
    // Binary OFF puts its data right after the header line: say so instead of "NUL byte".
    LineScanner first(text);
    std::vector<std::string_view> words;
    if (next_tokens(first, words) && words.size() > 1 && words[0].size() >= 3 &&
        words[0].substr(words[0].size() - 3) == "OFF" && words[1] == "BINARY")
      fail(name, first.line_number(), "binary OFF is not supported");
  }
  refuse_nul_bytes(name, text);
  LineScanner lines(text);
  std::vector<std::string_view> tokens;
  if (!next_tokens(lines, tokens)) fail(name, lines.line_number(), "no OFF header");
  const std::string_view keyword = tokens[0];
  const bool is_off = keyword.size() >= 3 && keyword.substr(keyword.size() - 3) == "OFF";
  if (!is_off) fail(name, lines.line_number(), "expected the OFF header keyword, found '" + quote_bytes(keyword) + "'");
  std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  if (prefix.size() >= 2 && prefix.substr(0, 2) == "ST") prefix.remove_prefix(2);
  if (!prefix.empty() && prefix[0] == 'C') prefix.remove_prefix(1);
  if (!prefix.empty() && prefix[0] == 'N') prefix.remove_prefix(1);
  if (!prefix.empty() && prefix[0] == 'C') prefix.remove_prefix(1);
  if (!prefix.empty())
    fail(name, lines.line_number(), "OFF variant '" + quote_bytes(keyword) + "' is not supported (only 3D OFF, COFF, NOFF, STOFF)");
  std::size_t first_count = 1;
  if (tokens.size() > 1 && tokens[1] == "BINARY") fail(name, lines.line_number(), "binary OFF is not supported");
  if (tokens.size() == 1) {
    if (!next_tokens(lines, tokens)) fail(name, lines.line_number(), "file ends before the vertex and face counts");
    first_count = 0;
  }
  const int count_line = lines.line_number();
  if (tokens.size() < first_count + 2 || tokens.size() > first_count + 3)
    fail(name, count_line, "expected '#vertices #faces [#edges]' after OFF");
  const std::int64_t nv = parse_count(name, count_line, tokens[first_count], "vertex count");
  const std::int64_t nf = parse_count(name, count_line, tokens[first_count + 1], "face count");
  if (tokens.size() == first_count + 3) parse_count(name, count_line, tokens[first_count + 2], "edge count");
  if (nv > kMaxVertices) fail(name, count_line, "header claims " + std::to_string(nv) + " vertices; the supported maximum is " + std::to_string(kMaxVertices));
  if (nf > kMaxFaces) fail(name, count_line, "header claims " + std::to_string(nf) + " faces; the supported maximum is " + std::to_string(kMaxFaces));
  const std::uint64_t remaining = text.size() - lines.offset();
  const std::uint64_t smallest = 6 * static_cast<std::uint64_t>(nv) + 8 * static_cast<std::uint64_t>(nf);
  if (smallest > remaining + 1) {  // + 1: the last line may lack its newline
    fail(name, count_line, "header claims " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                               " faces, more than the remaining " + std::to_string(remaining) + " bytes can hold");
  }

  RawMeshBuilder builder(name, MeshFormat::off, true);
  builder.reserve(nv, nf);
  for (std::int64_t i = 0; i < nv; ++i) {
    if (!next_tokens(lines, tokens))
      fail(name, lines.line_number(), "file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    const int line = lines.line_number();
    if (tokens.size() < 3) fail(name, line, "vertex needs 3 coordinates, found " + std::to_string(tokens.size()));
    double xyz[3];
    for (std::size_t k = 0; k < tokens.size(); ++k) {
      double value = 0;
      if (!parse_real(tokens[k], value)) fail(name, line, "coordinate '" + quote_bytes(tokens[k]) + "' is not a number");
      if (k < 3) xyz[k] = value;
    }
    builder.add_vertex(xyz[0], xyz[1], xyz[2], line);
  }
  std::vector<int> corners;
  for (std::int64_t f = 0; f < nf; ++f) {
    if (!next_tokens(lines, tokens))
      fail(name, lines.line_number(), "file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const int line = lines.line_number();
    std::int64_t n = 0;
    bool overflow = false;
    if (!parse_integer(tokens[0], n, overflow) || overflow)
      fail(name, line, "face corner count '" + quote_bytes(tokens[0]) + "' is not an integer");
    if (n < 3) fail(name, line, "face has " + std::to_string(n) + " corners (at least 3 needed)");
    if (n > static_cast<std::int64_t>(tokens.size()) - 1)
      fail(name, line, "face announces " + std::to_string(n) + " corners but the line has " + std::to_string(tokens.size() - 1) + " numbers");
    corners.resize(static_cast<std::size_t>(n));
    for (std::int64_t k = 0; k < n; ++k) {
      const std::string_view token = tokens[static_cast<std::size_t>(k + 1)];
      std::int64_t index = 0;
      if (!parse_integer(token, index, overflow)) fail(name, line, "vertex index '" + quote_bytes(token) + "' is not an integer");
      corners[static_cast<std::size_t>(k)] =
          overflow || index < std::numeric_limits<int>::min() + 1 || index > std::numeric_limits<int>::max()
              ? kIndexOverflow
              : static_cast<int>(index);
    }
    for (std::size_t k = static_cast<std::size_t>(n) + 1; k < tokens.size(); ++k) {
      double ignored = 0;
      if (!parse_real(tokens[k], ignored)) fail(name, line, "colour value '" + quote_bytes(tokens[k]) + "' is not a number");
    }
    builder.add_polygon(corners.data(), static_cast<int>(n), line);
  }
  if (next_tokens(lines, tokens))
    builder.warnings().push_back("text after the last face (line " + std::to_string(lines.line_number()) + ") ignored");
  return builder.finish();
}

}  // namespace offsetopt
