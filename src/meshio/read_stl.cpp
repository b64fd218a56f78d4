#include "meshio/read_stl.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "meshio/load_mesh.h"
#include "meshio/read_text.h"

namespace offsetopt {

namespace {

std::uint32_t read_u32_le(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

float read_f32_le(const unsigned char* p) {
  const std::uint32_t bits = read_u32_le(p);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::uint64_t binary_size_for(std::uint64_t count) { return 84 + 50 * count; }

std::uint32_t header_count(const std::string& bytes) {
  return read_u32_le(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
}

bool starts_with_solid(const std::string& bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n')) ++i;
  return bytes.size() - i >= 5 && equals_ignoring_case(std::string_view(bytes).substr(i, 5), "solid") &&
         (bytes.size() - i == 5 || std::strchr(" \t\r\n", bytes[i + 5]) != nullptr);
}

// Corners in file order -> welded vertices in order of first appearance. Coordinates are float
// for binary STL (exact, and half the memory) and double for ASCII STL. `corner_line` and
// `triangle_line` are empty for binary files.
template <typename Real>
RawMesh weld(const std::string& name, MeshFormat format, const std::vector<Real>& corner_xyz,
             const std::vector<int>& corner_line, const std::vector<int>& triangle_line,
             std::vector<std::string> warnings) {
  const std::size_t corners = corner_xyz.size() / 3;
  using Bits = std::conditional_t<sizeof(Real) == 4, std::uint32_t, std::uint64_t>;
  // Packed keys sort fast: finite corners by value, non-finite ones after them by bit pattern
  // (NaN has no order), ties by corner number so the first corner of each group comes first.
  struct Key {
    Real xyz[3];
    std::uint32_t corner;
    bool finite;
  };
  std::vector<Key> keys(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    Key& k = keys[c];
    for (int i = 0; i < 3; ++i) k.xyz[i] = corner_xyz[3 * c + static_cast<std::size_t>(i)];
    k.corner = static_cast<std::uint32_t>(c);
    k.finite = std::isfinite(k.xyz[0]) && std::isfinite(k.xyz[1]) && std::isfinite(k.xyz[2]);
  }
  auto bits = [](Real x) {
    Bits b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  std::sort(keys.begin(), keys.end(), [&bits](const Key& a, const Key& b) {
    if (a.finite != b.finite) return a.finite;
    for (int k = 0; k < 3; ++k) {
      if (a.finite) {
        if (a.xyz[k] < b.xyz[k]) return true;
        if (b.xyz[k] < a.xyz[k]) return false;
      } else if (bits(a.xyz[k]) != bits(b.xyz[k])) {
        return bits(a.xyz[k]) < bits(b.xyz[k]);
      }
    }
    return a.corner < b.corner;
  });
  auto same_position = [&bits](const Key& a, const Key& b) {
    if (a.finite != b.finite) return false;
    for (int k = 0; k < 3; ++k)
      if (a.finite ? !(a.xyz[k] == b.xyz[k]) : bits(a.xyz[k]) != bits(b.xyz[k])) return false;
    return true;
  };
  // representative[c] = first corner (in file order) at the same position.
  std::vector<std::uint32_t> representative(corners);
  for (std::size_t i = 0; i < corners;) {
    std::size_t j = i + 1;
    while (j < corners && same_position(keys[i], keys[j])) ++j;
    for (std::size_t k = i; k < j; ++k) representative[keys[k].corner] = keys[i].corner;
    i = j;
  }
  std::vector<Key>().swap(keys);
  RawMeshBuilder builder(name, format, !corner_line.empty());
  builder.warnings() = std::move(warnings);
  std::vector<int> vertex_of(corners, -1);
  std::vector<int> triangle_corners(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    const std::uint32_t r = representative[c];
    if (vertex_of[r] < 0) {
      vertex_of[r] = static_cast<int>(builder.vertex_count());
      builder.add_vertex(corner_xyz[3 * c], corner_xyz[3 * c + 1], corner_xyz[3 * c + 2],
                         corner_line.empty() ? 0 : corner_line[c]);
    }
    triangle_corners[c] = vertex_of[r];
  }
  builder.reserve(0, static_cast<std::int64_t>(corners / 3));
  for (std::size_t t = 0; t < corners / 3; ++t)
    builder.add_polygon(&triangle_corners[3 * t], 3, triangle_line.empty() ? 0 : triangle_line[t]);
  return builder.finish();
}

RawMesh read_binary(const std::string& name, const std::string& bytes, std::vector<std::string> warnings) {
  const std::uint64_t count = header_count(bytes);
  if (static_cast<std::int64_t>(count) > kMaxFaces) {
    throw MeshInputError(name + ": binary STL has " + std::to_string(count) + " triangles; the supported maximum is " +
                         std::to_string(kMaxFaces));
  }
  std::vector<float> corner_xyz(static_cast<std::size_t>(9 * count));
  const unsigned char* p = reinterpret_cast<const unsigned char*>(bytes.data()) + 84;
  for (std::uint64_t t = 0; t < count; ++t, p += 50)
    for (int k = 0; k < 9; ++k) corner_xyz[static_cast<std::size_t>(9 * t + k)] = read_f32_le(p + 12 + 4 * k);
  return weld(name, MeshFormat::stl_binary, corner_xyz, {}, {}, std::move(warnings));
}

// Whitespace tokens with their line numbers.
class Tokens {
 public:
  Tokens(const std::string& name, const std::string& text) : name_(name), text_(text) {}
  bool next(std::string_view& token) {
    return next_token(text_, position_, line_, token);
  }
  void skip_line() {
    while (position_ < text_.size() && text_[position_] != '\n' && text_[position_] != '\r') ++position_;
  }
  int line() const { return line_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw MeshInputError(name_ + ":" + std::to_string(line_) + ": " + what);
  }
  void expect(const char* keyword) {
    std::string_view token;
    if (!next(token)) fail(std::string("file ends where '") + keyword + "' was expected");
    if (!equals_ignoring_case(token, keyword))
      fail(std::string("expected '") + keyword + "', found '" + quote_bytes(token) + "'");
  }
  double number(const char* what) {
    std::string_view token;
    if (!next(token)) fail(std::string("file ends inside a ") + what);
    double value = 0;
    if (!parse_real(token, value)) fail(std::string(what) + " '" + quote_bytes(token) + "' is not a number");
    return value;
  }

 private:
  const std::string& name_;
  const std::string& text_;
  std::size_t position_ = 0;
  int line_ = 1;
};

RawMesh read_ascii(const std::string& name, const std::string& text) {
  Tokens tokens(name, text);
  std::vector<double> corner_xyz;
  std::vector<int> corner_line, triangle_line;
  std::vector<std::string> warnings;
  tokens.expect("solid");
  tokens.skip_line();  // the solid's name
  std::string_view token;
  bool ended = false;
  while (tokens.next(token)) {
    if (ended) {
      if (!equals_ignoring_case(token, "solid"))
        tokens.fail("expected 'solid' or the end of the file after 'endsolid', found '" + quote_bytes(token) + "'");
      tokens.skip_line();
      ended = false;
      continue;
    }
    if (equals_ignoring_case(token, "endsolid")) {
      tokens.skip_line();
      ended = true;
      continue;
    }
    if (!equals_ignoring_case(token, "facet")) tokens.fail("expected 'facet' or 'endsolid', found '" + quote_bytes(token) + "'");
    const int facet_line = tokens.line();
    if (static_cast<std::int64_t>(corner_xyz.size() / 9) >= kMaxFaces)
      tokens.fail("more than " + std::to_string(kMaxFaces) + " triangles (the supported maximum)");
    tokens.expect("normal");
    for (int k = 0; k < 3; ++k) tokens.number("normal component");
    tokens.expect("outer");
    tokens.expect("loop");
    for (int corner = 0; corner < 3; ++corner) {
      tokens.expect("vertex");
      corner_line.push_back(tokens.line());
      for (int k = 0; k < 3; ++k) corner_xyz.push_back(tokens.number("coordinate"));
    }
    triangle_line.push_back(facet_line);
    tokens.expect("endloop");
    tokens.expect("endfacet");
  }
  if (!ended) warnings.push_back("ASCII STL ends without 'endsolid'");
  return weld(name, MeshFormat::stl_ascii, corner_xyz, corner_line, triangle_line, std::move(warnings));
}

}  // namespace

bool looks_like_binary_stl(const std::string& bytes) {
  return bytes.size() >= 84 && binary_size_for(header_count(bytes)) == bytes.size();
}

RawMesh read_stl(const std::string& name, const std::string& bytes) {
  if (looks_like_binary_stl(bytes)) return read_binary(name, bytes, {});
  const bool has_nul = std::memchr(bytes.data(), '\0', bytes.size()) != nullptr;
  if (starts_with_solid(bytes) && !has_nul) return read_ascii(name, bytes);
  if (bytes.size() < 84)
    throw MeshInputError(name + ": " + std::to_string(bytes.size()) +
                         " bytes: too short for a binary STL (84-byte header) and not an ASCII STL");
  const std::uint64_t count = header_count(bytes);
  const std::uint64_t needed = binary_size_for(count);
  if (needed > bytes.size()) {
    throw MeshInputError(name + ": binary STL header claims " + std::to_string(count) + " triangles (" +
                         std::to_string(needed) + " bytes) but the file has " + std::to_string(bytes.size()) +
                         " bytes (truncated, or not an STL file)");
  }
  std::vector<std::string> warnings{std::to_string(bytes.size() - needed) + " bytes after the last of " +
                                    std::to_string(count) + " triangles in the binary STL ignored"};
  return read_binary(name, bytes, std::move(warnings));
}

}  // namespace offsetopt
