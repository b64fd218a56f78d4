#include "io/json.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "util/format_double.h"

namespace offsetopt {

Json& Json::push_back(Json value) {
  if (type_ == Type::null) type_ = Type::array;
  if (type_ != Type::array) throw std::runtime_error("json: push_back on a non-array");
  array_.push_back(std::move(value));
  return array_.back();
}

Json& Json::set(const std::string& key, Json value) {
  Json& slot = (*this)[key];
  slot = std::move(value);
  return slot;
}

Json& Json::operator[](const std::string& key) {
  if (type_ == Type::null) type_ = Type::object;
  if (type_ != Type::object) throw std::runtime_error("json: key access on a non-object");
  for (auto& item : object_)
    if (item.first == key) return item.second;
  object_.emplace_back(key, Json());
  return object_.back().second;
}

const Json& Json::at(const std::string& key) const {
  if (type_ != Type::object) throw std::runtime_error("json: key access on a non-object");
  for (const auto& item : object_)
    if (item.first == key) return item.second;
  throw std::runtime_error("json: missing key '" + key + "'");
}

const Json& Json::at(std::size_t index) const {
  if (type_ != Type::array) throw std::runtime_error("json: index access on a non-array");
  if (index >= array_.size()) throw std::runtime_error("json: index out of range");
  return array_[index];
}

bool Json::contains(const std::string& key) const {
  if (type_ != Type::object) return false;
  for (const auto& item : object_)
    if (item.first == key) return true;
  return false;
}

std::size_t Json::size() const {
  if (type_ == Type::array) return array_.size();
  if (type_ == Type::object) return object_.size();
  return 0;
}

bool Json::as_bool() const {
  if (type_ != Type::boolean) throw std::runtime_error("json: not a bool");
  return bool_;
}

double Json::as_number() const {
  if (type_ == Type::number) return number_;
  if (type_ == Type::integer) return static_cast<double>(int_);
  throw std::runtime_error("json: not a number");
}

std::int64_t Json::as_integer() const {
  if (type_ != Type::integer) throw std::runtime_error("json: not an integer");
  return int_;
}

const std::string& Json::as_string() const {
  if (type_ != Type::string) throw std::runtime_error("json: not a string");
  return string_;
}

namespace {

void append_escaped(std::string& out, const std::string& s) {
  static const char* hex = "0123456789abcdef";
  out += '"';
  for (unsigned char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          out += "\\u00";
          out += hex[c >> 4];
          out += hex[c & 15];
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  out += '"';
}

bool is_scalar(const Json& j) {
  return j.type() != Json::Type::array && j.type() != Json::Type::object;
}

void newline(std::string& out, int indent, int depth) {
  out += '\n';
  out.append(static_cast<std::size_t>(indent * depth), ' ');
}

}  // namespace

void Json::dump_to(std::string& out, int indent, int depth) const {
  switch (type_) {
    case Type::null: out += "null"; return;
    case Type::boolean: out += bool_ ? "true" : "false"; return;
    case Type::integer: out += std::to_string(int_); return;
    case Type::number:
      if (std::isfinite(number_)) append_double(out, number_);
      else out += "null";
      return;
    case Type::string: append_escaped(out, string_); return;
    case Type::array: {
      if (array_.empty()) { out += "[]"; return; }
      bool flat = indent < 0 || array_.size() <= 16;
      for (const auto& e : array_) flat = flat && is_scalar(e);
      out += '[';
      for (std::size_t i = 0; i < array_.size(); ++i) {
        if (i) out += flat && indent >= 0 ? ", " : ",";
        if (!flat && indent >= 0) newline(out, indent, depth + 1);
        array_[i].dump_to(out, indent, depth + 1);
      }
      if (!flat && indent >= 0) newline(out, indent, depth);
      out += ']';
      return;
    }
    case Type::object: {
      if (object_.empty()) { out += "{}"; return; }
      out += '{';
      for (std::size_t i = 0; i < object_.size(); ++i) {
        if (i) out += ',';
        if (indent >= 0) newline(out, indent, depth + 1);
        append_escaped(out, object_[i].first);
        out += indent >= 0 ? ": " : ":";
        object_[i].second.dump_to(out, indent, depth + 1);
      }
      if (indent >= 0) newline(out, indent, depth);
      out += '}';
      return;
    }
  }
}

std::string Json::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  if (indent >= 0) out += '\n';
  return out;
}

namespace {

class Parser {
 public:
  explicit Parser(const std::string& text) : s_(text) {}

  Json parse_document() {
    Json value = parse_value(0);
    skip_space();
    if (pos_ != s_.size()) fail("trailing characters");
    return value;
  }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw std::runtime_error(std::string("json parse error at byte ") + std::to_string(pos_) + ": " + what);
  }
  void skip_space() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\n' || s_[pos_] == '\r' || s_[pos_] == '\t')) ++pos_;
  }
  bool consume(const char* word) {
    std::size_t n = std::char_traits<char>::length(word);
    if (s_.compare(pos_, n, word) == 0) { pos_ += n; return true; }
    return false;
  }

  Json parse_value(int depth) {
    if (depth > 256) fail("nesting too deep");
    skip_space();
    if (pos_ >= s_.size()) fail("unexpected end");
    char c = s_[pos_];
    if (c == '{') return parse_object(depth);
    if (c == '[') return parse_array(depth);
    if (c == '"') return Json(parse_string());
    if (consume("true")) return Json(true);
    if (consume("false")) return Json(false);
    if (consume("null")) return Json();
    return parse_number();
  }

  Json parse_object(int depth) {
    ++pos_;
    Json obj = Json::object();
    skip_space();
    if (pos_ < s_.size() && s_[pos_] == '}') { ++pos_; return obj; }
    for (;;) {
      skip_space();
      if (pos_ >= s_.size() || s_[pos_] != '"') fail("expected a key");
      std::string key = parse_string();
      skip_space();
      if (pos_ >= s_.size() || s_[pos_] != ':') fail("expected ':'");
      ++pos_;
      obj.set(key, parse_value(depth + 1));
      skip_space();
      if (pos_ < s_.size() && s_[pos_] == ',') { ++pos_; continue; }
      if (pos_ < s_.size() && s_[pos_] == '}') { ++pos_; return obj; }
      fail("expected ',' or '}'");
    }
  }

  Json parse_array(int depth) {
    ++pos_;
    Json arr = Json::array();
    skip_space();
    if (pos_ < s_.size() && s_[pos_] == ']') { ++pos_; return arr; }
    for (;;) {
      arr.push_back(parse_value(depth + 1));
      skip_space();
      if (pos_ < s_.size() && s_[pos_] == ',') { ++pos_; continue; }
      if (pos_ < s_.size() && s_[pos_] == ']') { ++pos_; return arr; }
      fail("expected ',' or ']'");
    }
  }

  std::string parse_string() {
    ++pos_;
    std::string out;
    while (pos_ < s_.size()) {
      char c = s_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in string");
      if (c != '\\') { out += c; continue; }
      if (pos_ >= s_.size()) break;
      char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          if (pos_ + 4 > s_.size()) fail("short \\u escape");
          unsigned code = 0;
          for (int i = 0; i < 4; ++i) {
            char h = s_[pos_++];
            code <<= 4;
            if (h >= '0' && h <= '9') code |= static_cast<unsigned>(h - '0');
            else if (h >= 'a' && h <= 'f') code |= static_cast<unsigned>(h - 'a' + 10);
            else if (h >= 'A' && h <= 'F') code |= static_cast<unsigned>(h - 'A' + 10);
            else fail("bad \\u escape");
          }
          // Reports only escape control characters; encode the BMP code point as UTF-8.
          if (code < 0x80) out += static_cast<char>(code);
          else if (code < 0x800) { out += static_cast<char>(0xC0 | (code >> 6)); out += static_cast<char>(0x80 | (code & 0x3F)); }
          else { out += static_cast<char>(0xE0 | (code >> 12)); out += static_cast<char>(0x80 | ((code >> 6) & 0x3F)); out += static_cast<char>(0x80 | (code & 0x3F)); }
          break;
        }
        default: fail("bad escape");
      }
    }
    fail("unterminated string");
  }

  Json parse_number() {
    std::size_t start = pos_;
    bool integral = true;
    if (pos_ < s_.size() && s_[pos_] == '-') ++pos_;
    while (pos_ < s_.size()) {
      char c = s_[pos_];
      if (c >= '0' && c <= '9') { ++pos_; continue; }
      if (c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-') { integral = false; ++pos_; continue; }
      break;
    }
    if (start == pos_) fail("unexpected character");
    std::string token = s_.substr(start, pos_ - start);
    char* end = nullptr;
    if (integral) {
      long long v = std::strtoll(token.c_str(), &end, 10);
      if (*end == '\0') return Json(v);
    }
    // strtod is locale-dependent only in its decimal point; reports are written with '.', and
    // the binary never calls setlocale, so the "C" locale is in force.
    double d = std::strtod(token.c_str(), &end);
    if (*end != '\0') fail("malformed number");
    return Json(d);
  }

  const std::string& s_;
  std::size_t pos_ = 0;
};

}  // namespace

Json Json::parse(const std::string& text) { return Parser(text).parse_document(); }

}  // namespace offsetopt
