#include "util/quote_bytes.h"

namespace offsetopt {

std::string quote_bytes(std::string_view bytes) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  const std::size_t limit = 40;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (out.size() >= limit) {
      out += "...";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(bytes[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\' && c != '\'') {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

}  // namespace offsetopt
