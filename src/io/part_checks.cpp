#include "io/part_checks.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cerrno>
#include <cstdio>
#include <cstring>

#ifdef WHISKER_HAVE_OPENEXR
#include <zlib.h>  // crc32_z: OpenEXR links zlib
#endif

#include "render/accumulation.h"
#include "scene/quote.h"

namespace whisker {

// Escaped here (scene/quote.h) as well as where a refusal is printed: the
// message itself is one line, whatever bytes a damaged header holds.
std::string cut_value(const std::string& v) {
  return v.size() <= 40 ? printable(v) : printable(v.substr(0, 40)) + "...";
}

namespace {

// The largest header attribute read: the settings JSON is a few KB; OpenEXR
// allocates whatever size an attribute claims before it reads it (a 2^31-1
// claim took 2.1 GB before the refusal).
constexpr std::uint32_t kMaxAttributeBytes = 1u << 20;

// The bytes of the channel list at head[at...] as OpenEXR reads it: per
// channel its name and 16 bytes (type, pLinear, reserved, sampling), then an
// empty name. ~0u if it does not end within `size` bytes.
std::uint32_t channel_list_size(const std::string& head, std::size_t at, std::uint32_t size) {
  const std::size_t end = std::min(head.size(), at + std::size_t(size));
  std::size_t p = at;
  while (p < end && head[p] != '\0') {
    const std::size_t z = head.find('\0', p);
    if (z == std::string::npos || z >= end) return ~0u;
    p = z + 1 + 16;
  }
  return p < end ? std::uint32_t(p + 1 - at) : ~0u;
}

}  // namespace

void check_header_sizes(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw AccumulationError(path + ": cannot open: " + std::strerror(errno));
  std::string head(64 * 1024, '\0');
  head.resize(std::fread(head.data(), 1, head.size(), f));
  long long file_size = -1;
  if (std::fseek(f, 0, SEEK_END) == 0) file_size = std::ftell(f);
  std::fclose(f);
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(head[at + k]);
    return v;
  };
  const auto bad = [&](const std::string& why) {
    throw AccumulationError(path + ": not an accumulation file as whisker writes it: " + why);
  };
  if (head.size() < 8 || u32(0) != 20000630u) bad("no OpenEXR magic number");
  const std::uint32_t version = u32(4);
  // Flags: 0x200 tiled, 0x800 deep, 0x1000 multi-part (OpenEXR file layout).
  if ((version & 0xff) != 2 || (version & (0x200 | 0x800 | 0x1000)) != 0)
    bad("OpenEXR version 2 single-part scanline expected");
  std::size_t at = 8;  // the next attribute's name
  const auto name_at = [&](std::size_t& pos) {
    const std::size_t end = head.find('\0', pos);
    if (end == std::string::npos || end - pos > 255) bad("header attribute names cut short");
    std::string n = head.substr(pos, end - pos);
    pos = end + 1;
    return n;
  };
  for (;;) {
    const std::string name = name_at(at);
    if (name.empty()) break;  // the end of the header
    const std::string type = name_at(at);
    if (at + 4 > head.size()) bad("header cut short");
    const std::uint32_t size = u32(at);
    at += 4;
    // OpenEXR reads a typed value by its type, whatever the size says (a
    // channel list up to its empty name, a box as 16 bytes): a size that
    // disagrees sets it reading the rest of the header from elsewhere. Only
    // the types a part holds, at the sizes their layout gives.
    std::uint32_t expect = size;
    if (type == "box2i" || type == "box2f" || type == "v2f") expect = type == "v2f" ? 8 : 16;
    else if (type == "compression" || type == "lineOrder") expect = 1;
    else if (type == "float") expect = 4;
    else if (type == "chlist") expect = channel_list_size(head, at, size);
    else if (type != "string") bad("header attribute " + cut_value(name) + " of type " + cut_value(type));
    if (size != expect) bad("header attribute " + cut_value(name) + " of " + std::to_string(size) + " bytes");
    if (size > kMaxAttributeBytes || (file_size >= 0 && at + size > std::uint64_t(file_size)))
      throw AccumulationError(path + ": header attribute " + cut_value(name) + " claims " +
                              std::to_string(size) + " bytes, in a file of " +
                              std::to_string(file_size) + " (at most " +
                              std::to_string(kMaxAttributeBytes) + " each); damaged?");
    if (at + size > head.size()) bad("header longer than 64 KB");
    at += size;
  }
  // The line offset table follows, up to the first chunk: a file cut short
  // (a copy that did not finish) has offsets past its end. Told here so that
  // a merge names it before it compares the parts' headers.
  const auto u64 = [&](std::size_t p) { return std::uint64_t(u32(p)) | (std::uint64_t(u32(p + 4)) << 32); };
  if (at + 8 > head.size() || file_size < 0) return;
  const std::uint64_t first = u64(at);
  for (std::size_t p = at; p + 8 <= head.size() && p < first; p += 8)
    if (u64(p) >= std::uint64_t(file_size))
      throw AccumulationError(path + ": cannot read as OpenEXR: a line offset points past the end of the file (cut short?)");
}


#ifdef WHISKER_HAVE_OPENEXR
std::uint32_t crc32_of(std::uint32_t crc, const void* data, std::size_t n) {
  return std::uint32_t(crc32_z(crc, static_cast<const Bytef*>(data), n));
}
#endif

std::string crc_text(std::uint32_t crc) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08x", unsigned(crc));
  return buf;
}

std::string checksum_text(std::uint32_t header, std::uint32_t pixels) {
  return "crc32 header " + crc_text(header) + " pixels " + crc_text(pixels);
}

bool parse_checksum(const std::string& v, std::uint32_t& header, std::uint32_t& pixels) {
  const auto hex = [&](std::size_t at, std::uint32_t& out) {
    for (std::size_t k = at; k < at + 8; ++k)
      if (!std::isxdigit(static_cast<unsigned char>(v[k])) || std::isupper(static_cast<unsigned char>(v[k])))
        return false;
    return std::from_chars(v.data() + at, v.data() + at + 8, out, 16).ec == std::errc();
  };
  return v.size() == 37 && v.compare(0, 13, "crc32 header ") == 0 && v.compare(21, 8, " pixels ") == 0 &&
         hex(13, header) && hex(29, pixels);
}

}  // namespace whisker
