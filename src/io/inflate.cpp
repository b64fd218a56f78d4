#include "io/inflate.h"

#include <array>
#include <cstdint>

namespace offsetopt {

namespace {

constexpr int kMaxBits = 15;  // longest Huffman code in DEFLATE

// Reads bits least significant first, as DEFLATE packs them (RFC 1951, 3.1.1). Past the end it
// records the overrun and yields zeros, so the caller checks `overrun` once per symbol.
class BitReader {
 public:
  explicit BitReader(std::string_view data) : data_(data) {}
  std::uint32_t bits(int count) {
    std::uint32_t value = 0;
    for (int i = 0; i < count; ++i) {
      if (position_ >= data_.size()) {
        overrun_ = true;
        return 0;
      }
      const std::uint32_t bit = (static_cast<unsigned char>(data_[position_]) >> bit_) & 1u;
      value |= bit << i;
      if (++bit_ == 8) {
        bit_ = 0;
        ++position_;
      }
    }
    return value;
  }
  void align_to_byte() {
    if (bit_ != 0) {
      bit_ = 0;
      ++position_;
    }
  }
  bool overrun() const { return overrun_; }
  std::size_t position() const { return position_ + (bit_ != 0 ? 1 : 0); }
  std::size_t byte_position() const { return position_; }
  std::string_view data() const { return data_; }
  void skip_bytes(std::size_t n) { position_ += n; }

 private:
  std::string_view data_;
  std::size_t position_ = 0;
  int bit_ = 0;
  bool overrun_ = false;
};

// A canonical Huffman code given by its code lengths (RFC 1951, 3.2.2): how many codes of each
// length, and the symbols in code order. Decoding walks one bit at a time, comparing the code so
// far with the first code of each length, so no table can be indexed out of range.
struct Huffman {
  std::array<int, kMaxBits + 1> count{};
  std::array<int, 288> symbol{};
  int symbols = 0;
};

// False when the lengths over-subscribe the code space (no prefix code has them). An incomplete
// code is accepted; reading one of its unused codes is an error at decode time.
bool build_huffman(const int* lengths, int n, Huffman& h) {
  h = Huffman{};
  h.symbols = n;
  for (int s = 0; s < n; ++s) ++h.count[lengths[s]];
  int left = 1;
  for (int len = 1; len <= kMaxBits; ++len) {
    left <<= 1;
    left -= h.count[len];
    if (left < 0) return false;
  }
  std::array<int, kMaxBits + 2> offset{};
  for (int len = 1; len <= kMaxBits; ++len) offset[len + 1] = offset[len] + h.count[len];
  for (int s = 0; s < n; ++s)
    if (lengths[s] != 0) h.symbol[offset[lengths[s]]++] = s;
  return true;
}

// The next symbol, or -1 for a code the table does not hold or input that ran out.
int decode(BitReader& in, const Huffman& h) {
  int code = 0, first = 0, index = 0;
  for (int len = 1; len <= kMaxBits; ++len) {
    code |= static_cast<int>(in.bits(1));
    if (in.overrun()) return -1;
    const int count = h.count[len];
    if (code - first < count) return h.symbol[index + (code - first)];
    index += count;
    first = (first + count) << 1;
    code <<= 1;
  }
  return -1;
}

constexpr std::array<int, 29> kLengthBase = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                             31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::array<int, 29> kLengthExtra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                              2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr std::array<int, 30> kDistanceBase = {1,    2,    3,    4,    5,    7,     9,     13,    17,  25,
                                               33,   49,   65,   97,   129,  193,   257,   385,   513, 769,
                                               1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::array<int, 30> kDistanceExtra = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                                6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

InflateResult failure(InflateStatus status, std::string message, const BitReader& in) {
  InflateResult r;
  r.status = status;
  r.message = std::move(message) + " at compressed byte " + std::to_string(in.byte_position());
  r.input_used = in.position();
  return r;
}

// Literal/length and distance symbols until end-of-block (symbol 256).
InflateResult inflate_codes(BitReader& in, const Huffman& lit, const Huffman& dist, std::size_t max_output,
                            std::string& out) {
  for (;;) {
    const int symbol = decode(in, lit);
    if (symbol < 0) return failure(in.overrun() ? InflateStatus::truncated : InflateStatus::bad_data,
                                   in.overrun() ? "compressed data ends inside a block" : "invalid literal/length code", in);
    if (symbol < 256) {
      if (out.size() >= max_output) return failure(InflateStatus::too_large, "output above the cap", in);
      out += static_cast<char>(symbol);
      continue;
    }
    if (symbol == 256) return InflateResult{};
    const int li = symbol - 257;
    if (li >= 29) return failure(InflateStatus::bad_data, "invalid length symbol " + std::to_string(symbol), in);
    const std::size_t length = static_cast<std::size_t>(kLengthBase[li]) + in.bits(kLengthExtra[li]);
    const int di = decode(in, dist);
    if (di < 0 || in.overrun())
      return failure(in.overrun() ? InflateStatus::truncated : InflateStatus::bad_data,
                     in.overrun() ? "compressed data ends inside a block" : "invalid distance code", in);
    if (di >= 30) return failure(InflateStatus::bad_data, "invalid distance symbol " + std::to_string(di), in);
    const std::size_t distance = static_cast<std::size_t>(kDistanceBase[di]) + in.bits(kDistanceExtra[di]);
    if (in.overrun()) return failure(InflateStatus::truncated, "compressed data ends inside a block", in);
    if (distance > out.size())
      return failure(InflateStatus::bad_data, "distance " + std::to_string(distance) + " reaches before the start", in);
    if (length > max_output - out.size()) return failure(InflateStatus::too_large, "output above the cap", in);
    // Byte by byte: a copy may overlap the bytes it produces (distance < length).
    std::size_t from = out.size() - distance;
    for (std::size_t k = 0; k < length; ++k) out += out[from + k];
  }
}

bool fixed_tables(Huffman& lit, Huffman& dist) {
  std::array<int, 288> lengths{};
  for (int s = 0; s < 288; ++s) lengths[s] = s < 144 ? 8 : s < 256 ? 9 : s < 280 ? 7 : 8;
  std::array<int, 30> dlengths{};
  dlengths.fill(5);
  return build_huffman(lengths.data(), 288, lit) && build_huffman(dlengths.data(), 30, dist);
}

// RFC 1951, 3.2.7: the code lengths of both codes, themselves Huffman-coded.
InflateResult dynamic_tables(BitReader& in, Huffman& lit, Huffman& dist) {
  const int nlen = static_cast<int>(in.bits(5)) + 257;
  const int ndist = static_cast<int>(in.bits(5)) + 1;
  const int ncode = static_cast<int>(in.bits(4)) + 4;
  if (in.overrun()) return failure(InflateStatus::truncated, "compressed data ends in a block header", in);
  if (nlen > 286 || ndist > 30)
    return failure(InflateStatus::bad_data, "too many length or distance codes (" + std::to_string(nlen) + ", " + std::to_string(ndist) + ")", in);
  static constexpr std::array<int, 19> kOrder = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};
  std::array<int, 19> code_lengths{};
  for (int i = 0; i < ncode; ++i) code_lengths[kOrder[i]] = static_cast<int>(in.bits(3));
  if (in.overrun()) return failure(InflateStatus::truncated, "compressed data ends in a block header", in);
  Huffman lencode;
  if (!build_huffman(code_lengths.data(), 19, lencode))
    return failure(InflateStatus::bad_data, "over-subscribed code-length code", in);
  std::array<int, 286 + 30> lengths{};
  int index = 0;
  while (index < nlen + ndist) {
    const int symbol = decode(in, lencode);
    if (symbol < 0) return failure(in.overrun() ? InflateStatus::truncated : InflateStatus::bad_data, "invalid code-length code", in);
    if (symbol < 16) {
      lengths[index++] = symbol;
      continue;
    }
    int value = 0, repeat = 0;
    if (symbol == 16) {
      if (index == 0) return failure(InflateStatus::bad_data, "length repeat with no previous length", in);
      value = lengths[index - 1];
      repeat = 3 + static_cast<int>(in.bits(2));
    } else if (symbol == 17) {
      repeat = 3 + static_cast<int>(in.bits(3));
    } else {
      repeat = 11 + static_cast<int>(in.bits(7));
    }
    if (in.overrun()) return failure(InflateStatus::truncated, "compressed data ends in a block header", in);
    if (index + repeat > nlen + ndist) return failure(InflateStatus::bad_data, "code lengths run past their count", in);
    for (int k = 0; k < repeat; ++k) lengths[index++] = value;
  }
  if (lengths[256] == 0) return failure(InflateStatus::bad_data, "no end-of-block code", in);
  if (!build_huffman(lengths.data(), nlen, lit)) return failure(InflateStatus::bad_data, "over-subscribed literal/length code", in);
  if (!build_huffman(lengths.data() + nlen, ndist, dist))
    return failure(InflateStatus::bad_data, "over-subscribed distance code", in);
  return InflateResult{};
}

}  // namespace

InflateResult inflate(std::string_view compressed, std::size_t max_output, std::string& out) {
  out.clear();
  BitReader in(compressed);
  // Each block consumes at least 3 bits; this cap only guards the loop itself.
  const std::size_t max_blocks = compressed.size() * 8 / 3 + 1;
  for (std::size_t block = 0; block < max_blocks; ++block) {
    const std::uint32_t last = in.bits(1);
    const std::uint32_t type = in.bits(2);
    if (in.overrun()) return failure(InflateStatus::truncated, "compressed data ends before the last block", in);
    if (type == 0) {
      in.align_to_byte();
      const std::size_t at = in.byte_position();
      const std::string_view data = in.data();
      if (data.size() < 4 || at > data.size() - 4) return failure(InflateStatus::truncated, "stored block header cut off", in);
      const auto byte = [&](std::size_t i) { return static_cast<std::uint32_t>(static_cast<unsigned char>(data[at + i])); };
      const std::uint32_t len = byte(0) | (byte(1) << 8);
      const std::uint32_t nlen = byte(2) | (byte(3) << 8);
      if ((len ^ 0xFFFFu) != nlen) return failure(InflateStatus::bad_data, "stored block length check fails", in);
      in.skip_bytes(4);
      if (len > data.size() - in.byte_position()) return failure(InflateStatus::truncated, "stored block cut off", in);
      if (len > max_output - out.size()) return failure(InflateStatus::too_large, "output above the cap", in);
      out.append(data.substr(in.byte_position(), len));
      in.skip_bytes(len);
    } else if (type == 1 || type == 2) {
      Huffman lit, dist;
      if (type == 1) {
        fixed_tables(lit, dist);
      } else {
        InflateResult r = dynamic_tables(in, lit, dist);
        if (r.status != InflateStatus::ok) return r;
      }
      InflateResult r = inflate_codes(in, lit, dist, max_output, out);
      if (r.status != InflateStatus::ok) return r;
    } else {
      return failure(InflateStatus::bad_data, "invalid block type 3", in);
    }
    if (last) {
      InflateResult r;
      r.input_used = in.position();
      return r;
    }
  }
  return failure(InflateStatus::bad_data, "more blocks than the data can hold", in);
}

}  // namespace offsetopt
