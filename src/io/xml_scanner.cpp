#include "io/xml_scanner.h"

#include <cstdint>

#include "util/quote_bytes.h"

namespace offsetopt {

namespace {

constexpr std::size_t kMaxDepth = 256;
constexpr std::size_t kMaxAttributes = 256;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool is_name_start(char c) {
  const unsigned char u = static_cast<unsigned char>(c);
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':' || u >= 0x80;
}
bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; }

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// One reference starting at raw[i] == '&': appends its character(s) and returns its length, or
// 0 when it is not a well-formed predefined entity or character reference.
std::size_t reference(std::string_view raw, std::size_t i, std::string* out) {
  const std::size_t semi = raw.find(';', i);
  if (semi == std::string_view::npos || semi - i > 12) return 0;
  const std::string_view body = raw.substr(i + 1, semi - i - 1);
  char c = 0;
  if (body == "lt") c = '<';
  else if (body == "gt") c = '>';
  else if (body == "amp") c = '&';
  else if (body == "quot") c = '"';
  else if (body == "apos") c = '\'';
  if (c) {
    if (out) *out += c;
    return semi - i + 1;
  }
  if (body.size() < 2 || body[0] != '#') return 0;
  const bool hex = body[1] == 'x';
  const std::string_view digits = body.substr(hex ? 2 : 1);
  if (digits.empty()) return 0;
  std::uint32_t cp = 0;
  for (const char d : digits) {
    std::uint32_t v;
    if (d >= '0' && d <= '9') v = static_cast<std::uint32_t>(d - '0');
    else if (hex && d >= 'a' && d <= 'f') v = static_cast<std::uint32_t>(d - 'a' + 10);
    else if (hex && d >= 'A' && d <= 'F') v = static_cast<std::uint32_t>(d - 'A' + 10);
    else return 0;
    cp = cp * (hex ? 16 : 10) + v;
    if (cp > 0x10FFFF) return 0;
  }
  if (cp == 0 || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  if (out) append_utf8(*out, cp);
  return semi - i + 1;
}

}  // namespace

std::string_view XmlScanner::local_name() const {
  const std::size_t colon = name_.find(':');
  return colon == std::string_view::npos ? name_ : name_.substr(colon + 1);
}

const std::string* XmlScanner::attribute(std::string_view qualified_name) const {
  for (std::size_t i = 0; i < attribute_count_; ++i)
    if (attributes_[i].name == qualified_name) return &attributes_[i].value;
  return nullptr;
}

bool XmlScanner::fail(const std::string& what) {
  error_ = "line " + std::to_string(line_) + ": malformed XML: " + what;
  return false;
}

void XmlScanner::advance(std::size_t n) {
  const std::size_t end = pos_ + n < text_.size() ? pos_ + n : text_.size();
  for (std::size_t i = pos_; i < end; ++i)
    if (text_[i] == '\n') ++line_;
  pos_ = end;
}

void XmlScanner::skip_whitespace() {
  while (pos_ < text_.size() && is_space(text_[pos_])) advance(1);
}

bool XmlScanner::skip_until(std::string_view terminator, const char* what) {
  const std::size_t end = text_.find(terminator, pos_);
  if (end == std::string_view::npos) return fail(std::string("unterminated ") + what);
  advance(end + terminator.size() - pos_);
  return true;
}

bool XmlScanner::read_name(std::string_view& name) {
  const std::size_t start = pos_;
  if (!is_name_start(peek())) return false;
  while (pos_ < text_.size() && is_name_char(text_[pos_])) ++pos_;  // names hold no newline
  name = text_.substr(start, pos_ - start);
  return true;
}

bool XmlScanner::decode(std::string_view raw, std::string& out) {
  out.clear();
  for (std::size_t i = 0; i < raw.size();) {
    const char c = raw[i];
    if (c == '<') return fail("'<' in an attribute value");
    if (c == '&') {
      const std::size_t n = reference(raw, i, &out);
      if (n == 0) return fail("unknown or malformed reference in an attribute value");
      i += n;
    } else {
      out += c;
      ++i;
    }
  }
  return true;
}

bool XmlScanner::check_text(std::string_view text) {
  const bool outside = stack_.empty();
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (outside && !is_space(c)) return fail(root_closed_ ? "text after the root element" : "text before the root element");
    if (c == '&') {
      const std::size_t n = reference(text, i, nullptr);
      if (n == 0) return fail("unknown or malformed reference in text");
      i += n - 1;
    }
  }
  return true;
}

bool XmlScanner::next() {
  if (pending_end_) {
    pending_end_ = false;
    kind_ = XmlTokenKind::end;
    stack_.pop_back();
    if (stack_.empty()) root_closed_ = true;
    return true;
  }
  for (;;) {
    // Character data up to the next markup.
    const std::size_t lt = text_.find('<', pos_);
    const std::size_t stop = lt == std::string_view::npos ? text_.size() : lt;
    if (!check_text(text_.substr(pos_, stop - pos_))) return false;
    advance(stop - pos_);
    if (lt == std::string_view::npos) {
      if (!stack_.empty()) return fail("the file ends inside element <" + quote_bytes(stack_.back()) + ">");
      if (!root_seen_) return fail("no root element");
      kind_ = XmlTokenKind::eof;
      return true;
    }
    tag_line_ = line_;
    if (text_.compare(pos_, 4, "<!--") == 0) {
      advance(4);
      if (!skip_until("-->", "comment")) return false;
      continue;
    }
    if (text_.compare(pos_, 2, "<?") == 0) {
      advance(2);
      if (!skip_until("?>", "processing instruction")) return false;
      continue;
    }
    if (text_.compare(pos_, 9, "<![CDATA[") == 0) {
      if (stack_.empty()) return fail("CDATA outside the root element");
      advance(9);
      if (!skip_until("]]>", "CDATA section")) return false;
      continue;
    }
    if (peek(1) == '!') return fail("DOCTYPE and other declarations are not supported");
    if (peek(1) == '/') {
      advance(2);
      std::string_view name;
      if (!read_name(name)) return fail("bad end tag");
      skip_whitespace();
      if (peek() != '>') return fail("bad end tag </" + quote_bytes(name) + ">");
      advance(1);
      if (stack_.empty() || stack_.back() != name)
        return fail("end tag </" + quote_bytes(name) + "> does not match " +
                    (stack_.empty() ? std::string("any open element") : "<" + quote_bytes(stack_.back()) + ">"));
      name_ = name;
      kind_ = XmlTokenKind::end;
      stack_.pop_back();
      if (stack_.empty()) root_closed_ = true;
      return true;
    }
    // A start tag.
    advance(1);
    std::string_view name;
    if (!read_name(name)) return fail("bad tag name");
    if (stack_.empty() && root_seen_) return fail("a second root element <" + quote_bytes(name) + ">");
    if (stack_.size() >= kMaxDepth) return fail("elements nested deeper than " + std::to_string(kMaxDepth));
    attribute_count_ = 0;
    for (;;) {
      const std::size_t before = pos_;
      skip_whitespace();
      if (peek() == '>' || (peek() == '/' && peek(1) == '>')) break;
      if (pos_ == before) return fail("expected whitespace, '>' or '/>' in <" + quote_bytes(name) + ">");
      std::string_view attr;
      if (!read_name(attr)) return fail("bad attribute name in <" + quote_bytes(name) + ">");
      skip_whitespace();
      if (peek() != '=') return fail("attribute '" + quote_bytes(attr) + "' without '='");
      advance(1);
      skip_whitespace();
      const char quote = peek();
      if (quote != '"' && quote != '\'') return fail("attribute '" + quote_bytes(attr) + "' value not quoted");
      const std::size_t close = text_.find(quote, pos_ + 1);
      if (close == std::string_view::npos) return fail("unterminated attribute value");
      if (attribute_count_ >= kMaxAttributes) return fail("more than " + std::to_string(kMaxAttributes) + " attributes");
      for (std::size_t i = 0; i < attribute_count_; ++i)
        if (attributes_[i].name == attr) return fail("duplicate attribute '" + quote_bytes(attr) + "'");
      if (attributes_.size() <= attribute_count_) attributes_.emplace_back();
      XmlAttribute& a = attributes_[attribute_count_++];
      a.name = attr;
      if (!decode(text_.substr(pos_ + 1, close - pos_ - 1), a.value)) return false;
      advance(close + 1 - pos_);
    }
    if (pos_ >= text_.size()) return fail("the file ends inside a tag");
    // Keep the vector's strings (their capacity is reused) but expose only this tag's attributes.
    const bool self_closing = peek() == '/';
    advance(self_closing ? 2 : 1);
    name_ = name;
    kind_ = XmlTokenKind::start;
    root_seen_ = true;
    stack_.push_back(name);
    pending_end_ = self_closing;
    return true;
  }
}

}  // namespace offsetopt
