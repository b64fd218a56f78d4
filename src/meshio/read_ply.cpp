#include "meshio/read_ply.h"

#include <cstring>

#include "meshio/load_mesh.h"
#include "meshio/read_text.h"

namespace offsetopt {

namespace {

enum class Scalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool parse_scalar_type(std::string_view word, Scalar& type) {
  struct Entry {
    const char* a;
    const char* b;
    Scalar type;
  };
  static const Entry kTypes[] = {{"char", "int8", Scalar::int8},       {"uchar", "uint8", Scalar::uint8},
                                 {"short", "int16", Scalar::int16},    {"ushort", "uint16", Scalar::uint16},
                                 {"int", "int32", Scalar::int32},      {"uint", "uint32", Scalar::uint32},
                                 {"float", "float32", Scalar::float32}, {"double", "float64", Scalar::float64}};
  for (const Entry& e : kTypes)
    if (word == e.a || word == e.b) {
      type = e.type;
      return true;
    }
  return false;
}

int size_of(Scalar type) {
  switch (type) {
    case Scalar::int8:
    case Scalar::uint8: return 1;
    case Scalar::int16:
    case Scalar::uint16: return 2;
    case Scalar::int32:
    case Scalar::uint32:
    case Scalar::float32: return 4;
    case Scalar::float64: return 8;
  }
  return 8;
}

bool is_integer(Scalar type) { return type != Scalar::float32 && type != Scalar::float64; }

struct Property {
  std::string name;
  bool is_list = false;
  Scalar count_type = Scalar::uint8;
  Scalar type = Scalar::float32;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  int line = 0;
  std::vector<Property> properties;
  int x = -1, y = -1, z = -1, indices = -1;  // positions of the properties we use
};

enum class Encoding { ascii, little, big };

[[noreturn]] void fail_line(const std::string& name, int line, const std::string& what) {
  throw MeshInputError(name + ":" + std::to_string(line) + ": " + what);
}

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }
std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
  return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b;
}

std::string element_instance(const Element& element, std::uint64_t index) {
  return "element '" + quote_bytes(element.name) + "' number " + std::to_string(index);
}

// Binary data after the header.
class BinaryCursor {
 public:
  BinaryCursor(const std::string& name, const std::string& bytes, std::size_t start, bool big_endian)
      : name_(name), data_(reinterpret_cast<const unsigned char*>(bytes.data())), size_(bytes.size()),
        position_(start), big_endian_(big_endian) {}
  std::size_t remaining() const { return size_ - position_; }
  // The element instance being read, named in error messages.
  void set_context(const Element* element, std::uint64_t index) {
    element_ = element;
    index_ = index;
  }
  void need(std::uint64_t n) const {
    if (n > remaining())
      throw MeshInputError(name_ + ": binary data ends inside " + element_instance(*element_, index_) + " (truncated file)");
  }
  void skip(std::uint64_t n) {
    need(n);
    position_ += static_cast<std::size_t>(n);
  }
  // Reads one scalar; integers exactly (as int64), floats widened to double.
  void read(Scalar type, std::int64_t& integer, double& real) {
    const int n = size_of(type);
    need(static_cast<std::uint64_t>(n));
    std::uint64_t bits = 0;
    for (int i = 0; i < n; ++i) {
      const std::uint64_t byte = data_[position_ + static_cast<std::size_t>(big_endian_ ? i : n - 1 - i)];
      bits = bits << 8 | byte;
    }
    position_ += static_cast<std::size_t>(n);
    switch (type) {
      case Scalar::int8: integer = static_cast<std::int8_t>(bits); break;
      case Scalar::uint8: integer = static_cast<std::uint8_t>(bits); break;
      case Scalar::int16: integer = static_cast<std::int16_t>(bits); break;
      case Scalar::uint16: integer = static_cast<std::uint16_t>(bits); break;
      case Scalar::int32: integer = static_cast<std::int32_t>(bits); break;
      case Scalar::uint32: integer = static_cast<std::uint32_t>(bits); break;
      case Scalar::float32: {
        const std::uint32_t b32 = static_cast<std::uint32_t>(bits);
        float f;
        std::memcpy(&f, &b32, sizeof f);
        real = f;
        return;
      }
      case Scalar::float64: {
        double d;
        std::memcpy(&d, &bits, sizeof d);
        real = d;
        return;
      }
    }
    real = static_cast<double>(integer);
  }

 private:
  const std::string& name_;
  const unsigned char* data_;
  std::size_t size_;
  std::size_t position_;
  bool big_endian_;
  const Element* element_ = nullptr;
  std::uint64_t index_ = 0;
};

// Whitespace tokens of the ASCII body with line numbers.
class TextCursor {
 public:
  TextCursor(const std::string& name, const std::string& text, std::size_t start, int line)
      : name_(name), text_(text), position_(start), line_(line) {}
  std::size_t remaining() const { return text_.size() - position_; }
  int line() const { return line_; }
  bool next(std::string_view& token) {
    return next_token(text_, position_, line_, token);
  }
  std::string_view take(const Element& element, std::uint64_t index) {
    std::string_view token;
    if (!next(token)) fail_line(name_, line_, "file ends inside " + element_instance(element, index));
    return token;
  }

 private:
  const std::string& name_;
  const std::string& text_;
  std::size_t position_;
  int line_;
};

int index_from(std::int64_t value) {
  return value < std::numeric_limits<int>::min() + 1 || value > std::numeric_limits<int>::max() ? kIndexOverflow
                                                                                                : static_cast<int>(value);
}

struct PlyHeader {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  std::size_t body = 0;  // byte offset of the data
  int body_line = 0;     // its line number (ASCII)
};

// One 'property' line (tokens split), added to the last element; notes the positions of x, y, z
// in 'vertex' and of the index list in 'face'.
void add_property(const std::string& name, int number, const std::vector<std::string_view>& tokens,
                  std::vector<Element>& elements) {
  if (elements.empty()) fail_line(name, number, "property before any element");
  Property property;
  if (tokens.size() == 5 && tokens[1] == "list") {
    property.is_list = true;
    if (!parse_scalar_type(tokens[2], property.count_type) || !parse_scalar_type(tokens[3], property.type))
      fail_line(name, number, "unknown type in list property");
    if (!is_integer(property.count_type))
      fail_line(name, number, "list count type '" + quote_bytes(tokens[2]) + "' is not an integer type");
    property.name = std::string(tokens[4]);
  } else if (tokens.size() == 3) {
    if (!parse_scalar_type(tokens[1], property.type))
      fail_line(name, number, "unknown property type '" + quote_bytes(tokens[1]) + "'");
    property.name = std::string(tokens[2]);
  } else {
    fail_line(name, number, "expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
  }
  Element& element = elements.back();
  const int position = static_cast<int>(element.properties.size());
  if (element.name == "vertex" && !property.is_list) {
    if (property.name == "x") element.x = position;
    if (property.name == "y") element.y = position;
    if (property.name == "z") element.z = position;
  }
  if (element.name == "face" && property.is_list && (property.name == "vertex_indices" || property.name == "vertex_index")) {
    if (!is_integer(property.type))
      fail_line(name, number, "face index type '" + quote_bytes(tokens[3]) + "' is not an integer type");
    element.indices = position;
  }
  element.properties.push_back(property);
}

// Header: text lines up to "end_header"; the body starts right after its line end.
PlyHeader read_header(const std::string& name, const std::string& bytes) {
  LineScanner lines(bytes);
  std::string_view line;
  std::vector<std::string_view> tokens;
  if (!lines.next(line) || line != "ply") throw MeshInputError(name + ": not a PLY file (first line is not 'ply')");
  PlyHeader header;
  bool have_format = false, have_end = false;
  while (lines.next(line)) {
    const int number = lines.line_number();
    if (line.find('\0') != std::string_view::npos) fail_line(name, number, "binary data (byte 0x00) in the PLY header");
    split_tokens(line, tokens, true);
    if (tokens.empty()) continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      have_end = true;
      break;
    }
    if (keyword == "format") {
      if (tokens.size() != 3 || tokens[2] != "1.0") fail_line(name, number, "expected 'format <encoding> 1.0'");
      if (tokens[1] == "ascii") header.encoding = Encoding::ascii;
      else if (tokens[1] == "binary_little_endian") header.encoding = Encoding::little;
      else if (tokens[1] == "binary_big_endian") header.encoding = Encoding::big;
      else fail_line(name, number, "unknown PLY format '" + quote_bytes(tokens[1]) + "'");
      have_format = true;
    } else if (keyword == "element") {
      if (tokens.size() != 3) fail_line(name, number, "expected 'element <name> <count>'");
      std::int64_t count = 0;
      bool overflow = false;
      if (!parse_integer(tokens[2], count, overflow) || count < 0)
        fail_line(name, number, "element count '" + quote_bytes(tokens[2]) + "' is not a non-negative integer");
      const std::int64_t cap = tokens[1] == "vertex" ? kMaxVertices : kMaxFaces;
      if (overflow || count > cap) {
        fail_line(name, number, "header claims " + quote_bytes(tokens[2]) + " elements '" + quote_bytes(tokens[1]) +
                                    "'; the supported maximum is " + std::to_string(cap));
      }
      Element element;
      element.name = std::string(tokens[1]);
      element.count = static_cast<std::uint64_t>(count);
      element.line = number;
      header.elements.push_back(element);
    } else if (keyword == "property") {
      add_property(name, number, tokens, header.elements);
    } else {
      fail_line(name, number, "unknown PLY header line '" + quote_bytes(keyword) + "'");
    }
  }
  if (!have_end) throw MeshInputError(name + ": PLY header has no 'end_header'");
  if (!have_format) throw MeshInputError(name + ": PLY header has no 'format' line");
  header.body = lines.offset();
  header.body_line = lines.line_number() + 1;
  return header;
}

struct MeshElements {
  const Element* vertex = nullptr;
  const Element* face = nullptr;
};

// Which elements carry the mesh, and do the counts fit in the file?
MeshElements mesh_elements(const std::string& name, const std::string& bytes, const PlyHeader& header) {
  const std::vector<Element>& elements = header.elements;
  MeshElements found;
  std::uint64_t smallest = 0;
  for (const Element& element : elements) {
    if (element.name == "vertex") {
      if (found.vertex) fail_line(name, element.line, "second 'vertex' element");
      if (element.x < 0 || element.y < 0 || element.z < 0) fail_line(name, element.line, "vertex element lacks x, y or z");
      found.vertex = &element;
    }
    if (element.name == "face") {
      if (found.face) fail_line(name, element.line, "second 'face' element");
      if (element.indices < 0) fail_line(name, element.line, "face element has no list 'vertex_indices' or 'vertex_index'");
      found.face = &element;
    }
    if (element.name == "tristrips") fail_line(name, element.line, "triangle strips (element 'tristrips') are not supported");
    std::uint64_t per_instance = 0;
    for (const Property& p : element.properties)
      per_instance +=
          header.encoding == Encoding::ascii ? 2 : static_cast<std::uint64_t>(size_of(p.is_list ? p.count_type : p.type));
    smallest = saturating_add(smallest, saturating_mul(element.count, per_instance));
  }
  const std::uint64_t remaining = bytes.size() - header.body;
  if (smallest > remaining + (header.encoding == Encoding::ascii ? 1 : 0)) {
    // At most 8 elements named: a header of thousands of elements must not make a huge line.
    std::string claims;
    for (std::size_t i = 0; i < elements.size() && i < 8; ++i) {
      if (!claims.empty()) claims += ", ";
      claims += std::to_string(elements[i].count) + " " + quote_bytes(elements[i].name);
    }
    if (elements.size() > 8) claims += " and " + std::to_string(elements.size() - 8) + " more elements";
    throw MeshInputError(name + ": PLY header claims " + claims + ", more than the " + std::to_string(remaining) +
                         " bytes after the header can hold");
  }
  return found;
}

// The binary body: every element's instances in order, the mesh's ones into `builder`.
void read_binary_body(const std::string& name, const std::string& bytes, const PlyHeader& header,
                      const MeshElements& mesh, RawMeshBuilder& builder) {
  std::vector<int> corners;
  double xyz[3] = {0, 0, 0};
  BinaryCursor cursor(name, bytes, header.body, header.encoding == Encoding::big);
  for (const Element& element : header.elements) {
    // An element without properties holds no bytes: its count (up to the cap, unchecked
    // against the file size) must not cost a loop.
    if (element.properties.empty()) continue;
    for (std::uint64_t i = 0; i < element.count; ++i) {
      const bool is_vertex = &element == mesh.vertex, is_face = &element == mesh.face;
      cursor.set_context(&element, i);
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        std::int64_t integer = 0;
        double real = 0;
        const int position = static_cast<int>(p);
        if (!property.is_list) {
          if (is_vertex && (position == element.x || position == element.y || position == element.z)) {
            cursor.read(property.type, integer, real);
            xyz[position == element.x ? 0 : position == element.y ? 1 : 2] = real;
          } else {
            cursor.skip(static_cast<std::uint64_t>(size_of(property.type)));
          }
          continue;
        }
        cursor.read(property.count_type, integer, real);
        if (integer < 0) throw MeshInputError(name + ": negative list length in " + element_instance(element, i));
        const std::uint64_t n = static_cast<std::uint64_t>(integer);
        const std::uint64_t item = static_cast<std::uint64_t>(size_of(property.type));
        cursor.need(saturating_mul(n, item));
        if (is_face && position == element.indices) {
          if (n < 3) throw MeshInputError(name + ": face " + std::to_string(i) + " has " + std::to_string(n) + " corners (at least 3 needed)");
          corners.resize(static_cast<std::size_t>(n));
          for (std::uint64_t k = 0; k < n; ++k) {
            cursor.read(property.type, integer, real);
            corners[static_cast<std::size_t>(k)] = index_from(integer);
          }
          builder.add_polygon(corners.data(), static_cast<int>(n));
        } else {
          cursor.skip(n * item);
        }
      }
      if (is_vertex) builder.add_vertex(xyz[0], xyz[1], xyz[2]);
    }
  }
  if (cursor.remaining() > 0)
    builder.warnings().push_back(std::to_string(cursor.remaining()) + " bytes after the last PLY element ignored");
}

// The ASCII body: whitespace-separated tokens, every element's instances in order, the mesh's
// ones into `builder` with their line numbers.
void read_ascii_body(const std::string& name, const std::string& bytes, const PlyHeader& header,
                     const MeshElements& mesh, RawMeshBuilder& builder) {
  std::vector<int> corners;
  double xyz[3] = {0, 0, 0};
  TextCursor cursor(name, bytes, header.body, header.body_line);
  for (const Element& element : header.elements) {
    if (element.properties.empty()) continue;  // no tokens, however large the count
    for (std::uint64_t i = 0; i < element.count; ++i) {
      const bool is_vertex = &element == mesh.vertex, is_face = &element == mesh.face;
      int instance_line = 0;
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        const int position = static_cast<int>(p);
        const std::string_view first = cursor.take(element, i);
        if (p == 0) instance_line = cursor.line();
        if (!property.is_list) {
          double value = 0;
          if (!parse_real(first, value))
            fail_line(name, cursor.line(), "value '" + quote_bytes(first) + "' of property '" + quote_bytes(property.name) + "' is not a number");
          if (is_vertex && (position == element.x || position == element.y || position == element.z))
            xyz[position == element.x ? 0 : position == element.y ? 1 : 2] = value;
          continue;
        }
        std::int64_t n = 0;
        bool overflow = false;
        if (!parse_integer(first, n, overflow) || overflow || n < 0)
          fail_line(name, cursor.line(), "list length '" + quote_bytes(first) + "' is not a non-negative integer");
        if (static_cast<std::uint64_t>(n) > cursor.remaining() / 2 + 1)
          fail_line(name, cursor.line(), "list length " + std::to_string(n) + " exceeds what the rest of the file can hold");
        const bool indices = is_face && position == element.indices;
        if (indices) {
          if (n < 3) fail_line(name, cursor.line(), "face has " + std::to_string(n) + " corners (at least 3 needed)");
          corners.resize(static_cast<std::size_t>(n));
        }
        for (std::int64_t k = 0; k < n; ++k) {
          const std::string_view token = cursor.take(element, i);
          if (indices) {
            std::int64_t value = 0;
            if (!parse_integer(token, value, overflow))
              fail_line(name, cursor.line(), "vertex index '" + quote_bytes(token) + "' is not an integer");
            corners[static_cast<std::size_t>(k)] = overflow ? kIndexOverflow : index_from(value);
          } else {
            double ignored = 0;
            if (!parse_real(token, ignored)) fail_line(name, cursor.line(), "list item '" + quote_bytes(token) + "' is not a number");
          }
        }
        if (indices) builder.add_polygon(corners.data(), static_cast<int>(n), instance_line);
      }
      if (is_vertex) builder.add_vertex(xyz[0], xyz[1], xyz[2], instance_line);
    }
  }
  std::string_view extra;
  if (cursor.next(extra))
    builder.warnings().push_back("text after the last PLY element (line " + std::to_string(cursor.line()) + ") ignored");
}

}  // namespace

RawMesh read_ply(const std::string& name, const std::string& bytes) {
  const PlyHeader header = read_header(name, bytes);
  const MeshElements mesh = mesh_elements(name, bytes, header);
  const bool text = header.encoding == Encoding::ascii;
  const MeshFormat format = text ? MeshFormat::ply_ascii
                                 : header.encoding == Encoding::little ? MeshFormat::ply_binary_little
                                                                       : MeshFormat::ply_binary_big;
  RawMeshBuilder builder(name, format, text);
  builder.reserve(mesh.vertex ? static_cast<std::int64_t>(mesh.vertex->count) : 0,
                  mesh.face ? static_cast<std::int64_t>(mesh.face->count) : 0);
  if (text) read_ascii_body(name, bytes, header, mesh, builder);
  else read_binary_body(name, bytes, header, mesh, builder);
  return builder.finish();
}

}  // namespace offsetopt
