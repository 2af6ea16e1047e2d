// A part's (an accumulation file's) checks below OpenEXR: its header's
// bytes walked before OpenEXR reads them, and the CRC-32 checksums that its
// whisker.checksum attribute holds (accumulation_io.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace whisker {

// A value from a file, cut and escaped for a one-line message.
std::string cut_value(const std::string& v);

// Walks the attributes of the EXR header at `path` (OpenEXR file layout:
// magic 76 2f 31 01, a 4-byte version with flags, then name\0 type\0 int32
// size and the value, until an empty name) before OpenEXR reads it: every
// size must fit the file and 1 MB, and the line offsets the file. Only
// single-part scanline files, as write_accumulation writes them. Throws
// AccumulationError naming the path.
void check_header_sizes(const std::string& path);

// zlib's CRC-32 of `n` bytes at `data`, going on from `crc` (0 to start).
// Only in builds with OpenEXR (which links zlib).
std::uint32_t crc32_of(std::uint32_t crc, const void* data, std::size_t n);
// "1a2b3c4d".
std::string crc_text(std::uint32_t crc);
// whisker.checksum's value: "crc32 header 1a2b3c4d pixels 5e6f7a8b"; and
// back (false unless exactly that shape, lower-case hex).
std::string checksum_text(std::uint32_t header, std::uint32_t pixels);
bool parse_checksum(const std::string& v, std::uint32_t& header, std::uint32_t& pixels);

}  // namespace whisker
