// The byte formats under 3MF (issue 14): CRC-32 and inflate against known vectors (RFC 1952's
// check value, streams made by zlib). The zip container and the XML scanner are exercised through
// the 3MF reader and writer in tests/meshio/test_3mf.cpp.
#include <doctest/doctest.h>

#include <string>
#include <string_view>

#include "io/crc32.h"
#include "io/inflate.h"

using namespace offsetopt;

namespace {

std::string inflate_ok(std::string_view compressed) {
  std::string out;
  const InflateResult r = inflate(compressed, 1 << 20, out);
  CHECK(r.status == InflateStatus::ok);
  CAPTURE(r.message);
  return out;
}

}  // namespace

TEST_CASE("crc32: the standard check value and piecewise continuation") {
  CHECK(crc32("123456789") == 0xCBF43926u);
  CHECK(crc32("") == 0u);
  CHECK(crc32("The quick brown fox jumps over the lazy dog") == 0x414FA339u);
  CHECK(crc32("56789", crc32("1234")) == 0xCBF43926u);
}

TEST_CASE("inflate: stored, fixed and dynamic blocks made by zlib decode to the original") {
  const std::string hello = "hello hello hello hello";
  CHECK(inflate_ok(std::string_view("\x01\x17\x00\xe8\xff" "hello hello hello hello", 28)) == hello);
  CHECK(inflate_ok(std::string_view("\xcb\x48\xcd\xc9\xc9\x57\xc8\x40\x27\x01", 10)) == hello);
  std::string expected;
  for (int i = 0; i < 40; ++i)
    expected += "<vertex x=\"" + std::to_string(i) + "\" y=\"" + std::to_string(i * i % 17) + "\" z=\"" + std::to_string(i * 7 % 5) + "\"/>\n";
  const char dynamic[] =
      "\x7d\x93\x4b\x0e\xc2\x30\x0c\x05\xf7\x9c\xa2\xea\x05\x88\xed\x7c\xa5\xc2\x6d\x7a\x01\x84\x50\xe1\xf4\x08\x77\xc1\x93\x1d"
      "\x79\x93\xcd\x28\xce\xf8\xd9\xd9\x5e\xfb\xe3\xb9\x1f\xcb\x71\x5b\xd3\xba\xbc\xf5\xfc\xfc\xce\xeb\xfd\xb2\xfd\x19\x29\x23"
      "\x65\x6c\x18\x2b\xcb\xca\xb2\x61\xa2\x6c\x28\x23\xc3\xf2\x59\xb3\x2a\x14\x03\x8b\xc2\x3e\x95\xa9\xca\x78\x2a\xd3\xce\xa2"
      "\x65\x6a\xd3\x4f\x28\x53\x9d\x81\xd0\xea\x50\xc2\xba\x2e\x1d\x0a\x8c\x88\xa1\x15\x6b\x44\x82\x21\x58\x25\xca\x10\x9f\x53"
      "\x2a\x90\xbb\x33\xaa\xc1\xc0\xa8\xc1\xa4\x9d\x51\x87\x9b\x4e\x68\xc0\x9b\x56\x88\x13\xd8\x5a\x21\x26\x6c\xd4\xad\x50\x94"
      "\x11\x0b\xa4\x6b\x8d\x38\xe3\x60\x9c\x52\xc1\xa1\x3a\xa7\x8a\xd4\x39\x85\xab\xc4\x3d\x92\x1a\xd0\x8e\x75\x92\x84\x49\x58"
      "\x27\x21\x08\xd1\x2a\x49\xf8\xd5\x24\x18\x9c\x64\x18\xb9\x33\x2a\x70\xd3\x09\x55\x78\xd3\x09\x35\xb0\x75\x42\x3d\xda\x6d"
      "\x71\x19\x7d\x01";
  REQUIRE(expected.size() == 1163);
  const std::string_view stream(dynamic, sizeof dynamic - 1);
  REQUIRE(((static_cast<unsigned char>(stream[0]) >> 1) & 3) == 2);  // really a dynamic-Huffman block
  CHECK(inflate_ok(stream) == expected);

  SUBCASE("every cut of the stream is reported, never read past") {
    for (std::size_t n = 0; n < stream.size(); ++n) {
      std::string out;
      const InflateResult r = inflate(stream.substr(0, n), 1 << 20, out);
      // A cut inside the padding of the last byte may still hold the whole stream.
      CHECK((r.status != InflateStatus::ok || out == expected));
      CHECK(out.size() <= expected.size());
    }
  }
  SUBCASE("the output cap holds") {
    std::string out;
    const InflateResult r = inflate(stream, 1000, out);
    CHECK(r.status == InflateStatus::too_large);
    CHECK(out.size() <= 1000);
  }
  SUBCASE("block type 3 and a distance before the start are bad data") {
    std::string out;
    CHECK(inflate(std::string_view("\x07", 1), 100, out).status == InflateStatus::bad_data);
    // Fixed block: literal 'a', then length 3 at distance 2 with only one byte written.
    CHECK(inflate(std::string_view("\x4b\x04\x42\x00", 4), 100, out).status == InflateStatus::bad_data);
  }
}
