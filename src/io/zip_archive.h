// The zip container of 3MF packages (PKWARE APPNOTE.TXT 6.3.x, sections 4.3 and 4.4; 3MF Core
// Specification 1.3, section 2 "OPC"): local file headers, central directory, end record.
//
// Writing uses the STORED method only, with CRC-32 (io/crc32.h), version 2.0, no extra fields
// and a fixed timestamp (1980-01-01 00:00), so the same entries give byte-identical archives.
// Reading accepts STORED and DEFLATE (io/inflate.h) entries of a single-disk archive without
// zip64 or encryption, checks every offset and length against the archive's bytes and every
// entry's CRC-32, and never inflates more than a caller-given number of bytes.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace offsetopt {

struct ZipEntry {
  std::string name;  // path inside the archive, '/'-separated, no leading '/'
  std::string data;  // the uncompressed bytes
};

// The archive bytes; throws std::length_error when an entry or the archive needs zip64
// (4 GiB or more, or more than 65,535 entries).
std::string write_zip(const std::vector<ZipEntry>& entries);

// What the central directory says about one entry (nothing decompressed yet).
struct ZipEntryInfo {
  std::string name;
  std::uint16_t method = 0;   // 0 stored, 8 deflate
  std::uint16_t flags = 0;
  std::uint32_t crc = 0;
  std::uint64_t compressed_size = 0, size = 0;
  std::uint64_t data_offset = 0;  // of the entry's data in the archive, checked to fit
};

// The entries of `archive`, from its central directory. On a malformed archive returns false
// with `error` saying what and at which byte offset.
bool list_zip(std::string_view archive, std::vector<ZipEntryInfo>& entries, std::string& error);

// The uncompressed bytes of one listed entry, at most `max_size`; false with `error` on an
// unsupported method, corrupt data, a CRC mismatch or a size above the cap.
bool extract_zip_entry(std::string_view archive, const ZipEntryInfo& entry, std::size_t max_size, std::string& out,
                       std::string& error);

}  // namespace offsetopt
