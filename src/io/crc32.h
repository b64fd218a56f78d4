// CRC-32 as used by zip (ISO 3309 / ITU-T V.42: reflected polynomial 0xEDB88320, initial value
// and final xor 0xFFFFFFFF; PKWARE APPNOTE 4.4.7). "123456789" gives 0xCBF43926.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace offsetopt {

// The CRC of `bytes`; pass the previous result as `crc` to continue over several pieces.
std::uint32_t crc32(std::string_view bytes, std::uint32_t crc = 0);

}  // namespace offsetopt
