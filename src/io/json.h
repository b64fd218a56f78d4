// src/io: generic file and byte formats that know nothing of meshes as solids: JSON (this
// header), the zip container (zip_archive.h) with CRC-32 (crc32.h) and raw DEFLATE (inflate.h), a
// strict XML scanner (xml_scanner.h), and the .npy / CSV / Matrix Market / scalar PLY writers of
// `offsetopt basis` (basis_files.h). Layer: above geometry, beside meshio, which uses it; it may
// include util/, optim/, mesh/ (the Mesh type) and geometry/, never meshio/ or anything above.
//
// A minimal JSON document model and writer for reports. Objects keep insertion order so the
// output is byte-identical run to run; doubles use shortest round-trip text; non-finite doubles
// become null (JSON has no NaN). Parsing is provided only for tests and golden-file comparison.
#pragma once
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace offsetopt {

class Json {
 public:
  enum class Type { null, boolean, integer, number, string, array, object };

  Json() = default;                                   // null
  Json(std::nullptr_t) {}                             // null
  Json(bool b) : type_(Type::boolean), bool_(b) {}
  Json(int i) : type_(Type::integer), int_(i) {}
  Json(long i) : type_(Type::integer), int_(i) {}
  Json(long long i) : type_(Type::integer), int_(i) {}
  Json(unsigned i) : type_(Type::integer), int_(i) {}
  Json(unsigned long i) : type_(Type::integer), int_(static_cast<std::int64_t>(i)) {}
  Json(unsigned long long i) : type_(Type::integer), int_(static_cast<std::int64_t>(i)) {}
  Json(double d) : type_(Type::number), number_(d) {}
  Json(const char* s) : type_(Type::string), string_(s) {}
  Json(std::string s) : type_(Type::string), string_(std::move(s)) {}

  static Json array() { Json j; j.type_ = Type::array; return j; }
  static Json object() { Json j; j.type_ = Type::object; return j; }
  template <class Range>
  static Json array_of(const Range& values) {
    Json j = array();
    for (const auto& v : values) j.push_back(Json(v));
    return j;
  }
  static Json array_of(std::initializer_list<double> values) {
    Json j = array();
    for (double v : values) j.push_back(Json(v));
    return j;
  }

  Type type() const { return type_; }
  bool is_null() const { return type_ == Type::null; }

  // Array: append. Object: set (replaces an existing key in place, else appends).
  Json& push_back(Json value);
  Json& set(const std::string& key, Json value);
  Json& operator[](const std::string& key);  // object: inserts null if absent

  // Read access; throw std::runtime_error on a type mismatch or missing key.
  const Json& at(const std::string& key) const;
  const Json& at(std::size_t index) const;
  bool contains(const std::string& key) const;
  std::size_t size() const;
  bool as_bool() const;
  double as_number() const;  // Integer or Number
  std::int64_t as_integer() const;
  const std::string& as_string() const;
  const std::vector<std::pair<std::string, Json>>& items() const { return object_; }
  const std::vector<Json>& elements() const { return array_; }

  // indent < 0: compact, one line. indent >= 0: pretty with that many spaces, short numeric
  // arrays kept on one line so vectors and matrices stay readable.
  std::string dump(int indent = 2) const;

  // Strict RFC 8259 parse; throws std::runtime_error with the byte offset on malformed input.
  static Json parse(const std::string& text);

 private:
  void dump_to(std::string& out, int indent, int depth) const;

  Type type_ = Type::null;
  bool bool_ = false;
  std::int64_t int_ = 0;
  double number_ = 0.0;
  std::string string_;
  std::vector<Json> array_;
  std::vector<std::pair<std::string, Json>> object_;
};

}  // namespace offsetopt
