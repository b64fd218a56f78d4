// Untrusted bytes quoted for an error message, so a hostile file cannot flood the terminal or
// inject control characters: used by the mesh readers (meshio/) and the byte formats (io/).
#pragma once
#include <string>
#include <string_view>

namespace offsetopt {

// `bytes` quoted for an error message: printable ASCII kept, everything else as \xNN, cut to
// 40 characters with "..." so a hostile file cannot flood the terminal.
std::string quote_bytes(std::string_view bytes);

}  // namespace offsetopt
