// A small strict XML 1.0 scanner (W3C XML 1.0, 5th edition, sections 2.1-2.8 and 4.1) for the
// 3MF reader: start and end tags with attributes, checked for well-formedness (names match,
// attributes quoted and unique, one root element, entity references among the five predefined
// ones and character references), comments, processing instructions and CDATA skipped.
// Refused: DOCTYPE (no entity expansion, so no "billion laughs"), nesting deeper than 256,
// more than 256 attributes in one tag. Character data is checked, not returned.
// Linear in the input; every error names the line.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace offsetopt {

struct XmlAttribute {
  std::string_view name;
  std::string value;  // with references replaced
};

enum class XmlTokenKind { start, end, eof };

class XmlScanner {
 public:
  explicit XmlScanner(std::string_view text) : text_(text) {}

  // Moves to the next start or end tag (a self-closing tag gives a start, then an end), or to
  // eof once the root element is closed and only whitespace, comments and processing
  // instructions follow. False on malformed XML, with error() saying what at which line.
  bool next();

  XmlTokenKind kind() const { return kind_; }
  std::string_view name() const { return name_; }       // qualified name, prefix included
  std::string_view local_name() const;                  // name without its "prefix:"
  int line() const { return tag_line_; }                // line of the tag's '<'
  int depth() const { return static_cast<int>(stack_.size()); }  // open elements, this one included for a start
  // The value of the attribute with this qualified name, or nullptr.
  const std::string* attribute(std::string_view qualified_name) const;
  const std::string& error() const { return error_; }

 private:
  bool fail(const std::string& what);
  bool skip_until(std::string_view terminator, const char* what);
  bool check_text(std::string_view text);
  bool read_name(std::string_view& name);
  bool decode(std::string_view raw, std::string& out);
  void skip_whitespace();
  char peek(std::size_t ahead = 0) const { return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0'; }
  void advance(std::size_t n);

  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1, tag_line_ = 1;
  XmlTokenKind kind_ = XmlTokenKind::eof;
  std::string_view name_;
  std::vector<XmlAttribute> attributes_;  // the first attribute_count_ belong to this tag
  std::size_t attribute_count_ = 0;
  std::vector<std::string_view> stack_;
  bool pending_end_ = false, root_seen_ = false, root_closed_ = false;
  std::string error_;
};

}  // namespace offsetopt
