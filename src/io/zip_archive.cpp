#include "io/zip_archive.h"

#include <stdexcept>

#include "io/crc32.h"
#include "io/inflate.h"
#include "util/quote_bytes.h"

namespace offsetopt {

namespace {

constexpr std::uint32_t kLocalSignature = 0x04034b50u;
constexpr std::uint32_t kCentralSignature = 0x02014b50u;
constexpr std::uint32_t kEndSignature = 0x06054b50u;
constexpr std::uint16_t kDosDate1980 = (0 << 9) | (1 << 5) | 1;  // 1980-01-01: the earliest DOS date

void put16(std::string& out, std::uint32_t v) {
  out += static_cast<char>(v & 0xFF);
  out += static_cast<char>((v >> 8) & 0xFF);
}
void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xFFFF);
  put16(out, v >> 16);
}

std::uint32_t get16(std::string_view b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 8);
}
std::uint32_t get32(std::string_view b, std::size_t at) { return get16(b, at) | (get16(b, at + 2) << 16); }

}  // namespace

std::string write_zip(const std::vector<ZipEntry>& entries) {
  if (entries.size() > 0xFFFF) throw std::length_error("more than 65535 zip entries");
  std::string out, central;
  for (const ZipEntry& e : entries) {
    if (e.data.size() >= 0xFFFFFFFFu || e.name.size() > 0xFFFF)
      throw std::length_error(e.name + ": entry of " + std::to_string(e.data.size()) + " bytes needs zip64");
    const std::uint32_t offset = static_cast<std::uint32_t>(out.size());
    if (out.size() >= 0xFFFFFFFFu) throw std::length_error("archive above 4 GiB needs zip64");
    const std::uint32_t crc = crc32(e.data);
    const std::uint32_t size = static_cast<std::uint32_t>(e.data.size());
    // Local file header (APPNOTE 4.3.7).
    put32(out, kLocalSignature);
    put16(out, 20);  // version needed: 2.0
    put16(out, 0);   // flags
    put16(out, 0);   // method: stored
    put16(out, 0);   // time 00:00:00
    put16(out, kDosDate1980);
    put32(out, crc);
    put32(out, size);
    put32(out, size);
    put16(out, static_cast<std::uint32_t>(e.name.size()));
    put16(out, 0);  // extra field length
    out += e.name;
    out += e.data;
    // Central directory header (APPNOTE 4.3.12).
    put32(central, kCentralSignature);
    put16(central, 20);  // version made by: 2.0, MS-DOS attributes
    put16(central, 20);
    put16(central, 0);
    put16(central, 0);
    put16(central, 0);
    put16(central, kDosDate1980);
    put32(central, crc);
    put32(central, size);
    put32(central, size);
    put16(central, static_cast<std::uint32_t>(e.name.size()));
    put16(central, 0);  // extra
    put16(central, 0);  // comment
    put16(central, 0);  // disk number
    put16(central, 0);  // internal attributes
    put32(central, 0);  // external attributes
    put32(central, offset);
    central += e.name;
  }
  if (out.size() + central.size() >= 0xFFFFFFFFu) throw std::length_error("archive above 4 GiB needs zip64");
  const std::uint32_t central_offset = static_cast<std::uint32_t>(out.size());
  out += central;
  // End of central directory record (APPNOTE 4.3.16).
  put32(out, kEndSignature);
  put16(out, 0);
  put16(out, 0);
  put16(out, static_cast<std::uint32_t>(entries.size()));
  put16(out, static_cast<std::uint32_t>(entries.size()));
  put32(out, static_cast<std::uint32_t>(central.size()));
  put32(out, central_offset);
  put16(out, 0);  // comment length
  return out;
}

bool list_zip(std::string_view archive, std::vector<ZipEntryInfo>& entries, std::string& error) {
  entries.clear();
  const std::size_t n = archive.size();
  if (n < 22) {
    error = "not a zip archive (" + std::to_string(n) + " bytes, shorter than an end record)";
    return false;
  }
  // The end record sits in the last 22 + 65,535 bytes (its comment is at most 65,535 bytes);
  // search backwards so a comment that happens to hold the signature is not taken first.
  std::size_t end = std::string_view::npos;
  const std::size_t lowest = n > 22 + 0xFFFF ? n - 22 - 0xFFFF : 0;
  for (std::size_t at = n - 22 + 1; at-- > lowest;) {
    if (get32(archive, at) == kEndSignature && at + 22 + get16(archive, at + 20) == n) {
      end = at;
      break;
    }
  }
  if (end == std::string_view::npos) {
    error = "not a zip archive (no end of central directory record)";
    return false;
  }
  const std::uint32_t disk = get16(archive, end + 4), cd_disk = get16(archive, end + 6);
  const std::uint32_t count = get16(archive, end + 10);
  const std::uint32_t cd_size = get32(archive, end + 12), cd_offset = get32(archive, end + 16);
  if (disk != 0 || cd_disk != 0 || get16(archive, end + 8) != count) {
    error = "multi-disk zip archives are not supported (end record at byte " + std::to_string(end) + ")";
    return false;
  }
  if (count == 0xFFFF || cd_size == 0xFFFFFFFFu || cd_offset == 0xFFFFFFFFu) {
    error = "zip64 archives are not supported (end record at byte " + std::to_string(end) + ")";
    return false;
  }
  if (static_cast<std::uint64_t>(cd_offset) + cd_size > end) {
    error = "central directory (offset " + std::to_string(cd_offset) + ", " + std::to_string(cd_size) +
            " bytes) runs past the end record at byte " + std::to_string(end);
    return false;
  }
  std::size_t at = cd_offset;
  const std::size_t cd_end = static_cast<std::size_t>(cd_offset) + cd_size;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (at + 46 > cd_end || get32(archive, at) != kCentralSignature) {
      error = "central directory entry " + std::to_string(i) + " missing or cut off at byte " + std::to_string(at);
      return false;
    }
    ZipEntryInfo e;
    e.flags = static_cast<std::uint16_t>(get16(archive, at + 8));
    e.method = static_cast<std::uint16_t>(get16(archive, at + 10));
    e.crc = get32(archive, at + 16);
    e.compressed_size = get32(archive, at + 20);
    e.size = get32(archive, at + 24);
    const std::size_t name_len = get16(archive, at + 28), extra_len = get16(archive, at + 30), comment_len = get16(archive, at + 32);
    const std::uint32_t local = get32(archive, at + 42);
    if (at + 46 + name_len + extra_len + comment_len > cd_end) {
      error = "central directory entry " + std::to_string(i) + " runs past the directory at byte " + std::to_string(at);
      return false;
    }
    e.name.assign(archive.substr(at + 46, name_len));
    if (e.compressed_size == 0xFFFFFFFFu || e.size == 0xFFFFFFFFu || local == 0xFFFFFFFFu) {
      error = "entry '" + quote_bytes(e.name) + "' needs zip64, which is not supported (central directory byte " + std::to_string(at) + ")";
      return false;
    }
    // The local header repeats name and extra field, with lengths of its own.
    if (static_cast<std::uint64_t>(local) + 30 > cd_offset || get32(archive, local) != kLocalSignature) {
      error = "entry '" + quote_bytes(e.name) + "': no local header at byte " + std::to_string(local);
      return false;
    }
    const std::uint64_t data = static_cast<std::uint64_t>(local) + 30 + get16(archive, local + 26) + get16(archive, local + 28);
    if (data + e.compressed_size > cd_offset) {
      error = "entry '" + quote_bytes(e.name) + "': data (" + std::to_string(e.compressed_size) + " bytes at byte " + std::to_string(data) +
              ") runs past the central directory";
      return false;
    }
    e.data_offset = data;
    entries.push_back(std::move(e));
    at += 46 + name_len + extra_len + comment_len;
  }
  return true;
}

bool extract_zip_entry(std::string_view archive, const ZipEntryInfo& entry, std::size_t max_size, std::string& out,
                       std::string& error) {
  out.clear();
  const std::string where = "entry '" + quote_bytes(entry.name) + "'";
  if (entry.flags & 1u) {
    error = where + " is encrypted";
    return false;
  }
  if (entry.size > max_size) {
    error = where + " is " + std::to_string(entry.size) + " bytes uncompressed; the supported maximum is " + std::to_string(max_size);
    return false;
  }
  if (entry.data_offset + entry.compressed_size > archive.size()) {
    error = where + ": data runs past the archive";
    return false;
  }
  const std::string_view data = archive.substr(static_cast<std::size_t>(entry.data_offset), static_cast<std::size_t>(entry.compressed_size));
  if (entry.method == 0) {
    if (entry.compressed_size != entry.size) {
      error = where + ": stored entry with compressed size " + std::to_string(entry.compressed_size) + " != size " + std::to_string(entry.size);
      return false;
    }
    out.assign(data);
  } else if (entry.method == 8) {
    // The central directory's size is the cap: an archive cannot make us inflate more than it declares.
    const InflateResult r = inflate(data, static_cast<std::size_t>(entry.size), out);
    if (r.status != InflateStatus::ok) {
      error = where + ": " + (r.status == InflateStatus::too_large ? "inflates to more than the declared " + std::to_string(entry.size) + " bytes (" + r.message + ")"
                                                                    : "corrupt deflate data (" + r.message + ")");
      out.clear();
      return false;
    }
    if (out.size() != entry.size) {
      error = where + ": inflates to " + std::to_string(out.size()) + " bytes, the directory says " + std::to_string(entry.size);
      out.clear();
      return false;
    }
  } else {
    error = where + ": compression method " + std::to_string(entry.method) + " is not supported (only stored and deflate)";
    return false;
  }
  if (crc32(out) != entry.crc) {
    error = where + ": CRC-32 mismatch (data corrupt)";
    out.clear();
    return false;
  }
  return true;
}

}  // namespace offsetopt
