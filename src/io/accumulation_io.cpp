#include "io/accumulation_io.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <exception>
#include <filesystem>

#include "io/atomic_file.h"
#include "io/image_error.h"

#ifdef WHISKER_HAVE_OPENEXR
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#endif

namespace whisker {

namespace {

constexpr const char* kFormat = "whisker-accumulation 1";

// A double's 64 bits as two 32-bit words (EXR's UINT channels): exact by
// construction, whatever the value.
void split_bits(double d, std::uint32_t& hi, std::uint32_t& lo) {
  std::uint64_t u;
  std::memcpy(&u, &d, sizeof u);
  hi = std::uint32_t(u >> 32);
  lo = std::uint32_t(u);
}
double join_bits(std::uint32_t hi, std::uint32_t lo) {
  const std::uint64_t u = (std::uint64_t(hi) << 32) | lo;
  double d;
  std::memcpy(&d, &u, sizeof d);
  return d;
}

// The exact channels: four doubles per pixel (sum R, G, B and the luminance
// sum of squares), each as a .hi and a .lo word.
constexpr const char* kExact[4] = {"sum.R", "sum.G", "sum.B", "sumsq.Y"};

std::string text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// A value from a file, cut for a one-line message.
std::string cut(const std::string& v) { return v.size() <= 40 ? v : v.substr(0, 40) + "..."; }

// The largest header attribute read: the settings JSON is a few KB; OpenEXR
// allocates whatever size an attribute claims before it reads it (a 2^31-1
// claim took 2.1 GB before the refusal).
constexpr std::uint32_t kMaxAttributeBytes = 1u << 20;

// Walks the attributes of the EXR header (OpenEXR file layout: magic
// 76 2f 31 01, a 4-byte version with flags, then name\0 type\0 int32 size
// and the value, until an empty name) before OpenEXR reads it: every size
// must fit the file and kMaxAttributeBytes. Only single-part scanline files,
// as write_accumulation writes them.
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

[[maybe_unused]] void check_header_sizes(const std::string& path) {
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
    else if (type != "string") bad("header attribute " + cut(name) + " of type " + cut(type));
    if (size != expect) bad("header attribute " + cut(name) + " of " + std::to_string(size) + " bytes");
    if (size > kMaxAttributeBytes || (file_size >= 0 && at + size > std::uint64_t(file_size)))
      throw AccumulationError(path + ": header attribute " + cut(name) + " claims " +
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

}  // namespace

#ifdef WHISKER_HAVE_OPENEXR

void write_accumulation(const std::string& path, const Accumulation& acc) {
  const std::size_t pixels = std::size_t(acc.width) * acc.height;
  if (acc.width <= 0 || acc.height <= 0 || acc.sum.size() != pixels * 3 ||
      acc.sum_sq.size() != pixels)
    throw ImageError(path + ": empty or malformed accumulation");
  const Image mean = mean_image(snapshot_of(acc));
  // words[c][2p] = hi, words[c][2p+1] = lo of channel c of pixel p
  std::vector<std::uint32_t> words[4];
  for (int c = 0; c < 4; ++c) {
    words[c].resize(pixels * 2);
    for (std::size_t p = 0; p < pixels; ++p)
      split_bits(c < 3 ? acc.sum[3 * p + c] : acc.sum_sq[p], words[c][2 * p], words[c][2 * p + 1]);
  }
  write_file_atomically(path, [&](const std::string& tmp) {
    try {
      Imf::Header header(acc.width, acc.height);
      for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
      for (const char* c : kExact)
        for (const char* part : {".hi", ".lo"})
          header.channels().insert(std::string(c) + part, Imf::Channel(Imf::UINT));
      const auto attr = [&](const char* name, const std::string& value) {
        header.insert(std::string("whisker.") + name, Imf::StringAttribute(value));
      };
      attr("format", kFormat);
      attr("samples", ranges_to_string(acc.ranges));
      attr("scene", acc.id.scene);
      attr("scene_hash", acc.id.scene_hash);
      attr("settings", acc.id.settings);
      attr("passes", std::to_string(acc.counters.passes));
      attr("nan_count", std::to_string(acc.counters.nan_count));
      attr("rays", std::to_string(acc.counters.rays));
      attr("seconds", text(acc.counters.seconds));
      Imf::OutputFile file(tmp.c_str(), header);
      Imf::FrameBuffer fb;
      char* base = reinterpret_cast<char*>(const_cast<float*>(mean.rgb.data()));
      const std::size_t xs = 3 * sizeof(float), ys = xs * acc.width;
      for (int c = 0; c < 3; ++c)
        fb.insert(std::string(1, "RGB"[c]), Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
      const std::size_t wx = 2 * sizeof(std::uint32_t), wy = wx * acc.width;
      for (int c = 0; c < 4; ++c) {
        char* w = reinterpret_cast<char*>(words[c].data());
        fb.insert(std::string(kExact[c]) + ".hi", Imf::Slice(Imf::UINT, w, wx, wy));
        fb.insert(std::string(kExact[c]) + ".lo",
                  Imf::Slice(Imf::UINT, w + sizeof(std::uint32_t), wx, wy));
      }
      file.setFrameBuffer(fb);
      file.writePixels(acc.height);
      return true;
    } catch (const std::exception&) {
      return false;
    }
  });
}

namespace {

std::string attribute(const Imf::Header& h, const std::string& path, const char* name) {
  const auto* a = h.findTypedAttribute<Imf::StringAttribute>(std::string("whisker.") + name);
  if (!a)
    throw AccumulationError(path + ": not a whisker accumulation file (no whisker." +
                            std::string(name) + " attribute; write one with --out-sum)");
  return a->value();
}

// A count as the writer writes it: decimal digits that fit 64 bits (a
// 23-digit count wrapped around before).
std::uint64_t count_attribute(const Imf::Header& h, const std::string& path, const char* name) {
  const std::string v = attribute(h, path, name);
  std::uint64_t n = 0;
  const auto [end, err] = std::from_chars(v.data(), v.data() + v.size(), n);
  if (v.empty() || v[0] < '0' || v[0] > '9' || end != v.data() + v.size() || err != std::errc())
    throw AccumulationError(path + ": whisker." + name + " \"" + cut(v) +
                            "\" is not a count (decimal digits, below 2^64)");
  return n;
}

// Render seconds: a finite number >= 0, as the writer writes it.
double seconds_attribute(const Imf::Header& h, const std::string& path) {
  const std::string v = attribute(h, path, "seconds");
  double d = 0.0;
  const auto [end, err] = std::from_chars(v.data(), v.data() + v.size(), d);
  if (v.empty() || end != v.data() + v.size() || err != std::errc() || !std::isfinite(d) || d < 0)
    throw AccumulationError(path + ": whisker.seconds \"" + cut(v) +
                            "\" is not a finite number of seconds >= 0");
  return d;
}

Accumulation read(const std::string& path, bool with_sums) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw AccumulationError(path + ": no such file");
  check_header_sizes(path);
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& h = file.header();
    if (attribute(h, path, "format") != kFormat)
      throw AccumulationError(path + ": unknown accumulation format \"" +
                              attribute(h, path, "format") + "\" (expected " + kFormat + ")");
    Accumulation acc;
    if (!parse_ranges(attribute(h, path, "samples"), acc.ranges))
      throw AccumulationError(path + ": whisker.samples \"" + attribute(h, path, "samples") +
                              "\" is not a list of sorted ranges A:B");
    acc.id = {attribute(h, path, "scene"), attribute(h, path, "scene_hash"),
              attribute(h, path, "settings")};
    acc.counters.passes = count_attribute(h, path, "passes");
    acc.counters.nan_count = count_attribute(h, path, "nan_count");
    acc.counters.rays = count_attribute(h, path, "rays");
    acc.counters.seconds = seconds_attribute(h, path);
    const Imath::Box2i dw = h.dataWindow();
    // The header's size is checked before the pixels are allocated: a 35 KB
    // file claiming 40000 x 40000 pixels asked for 51 GB. Renders are at
    // most 16384 pixels a side and 4096 x 4096 in all (the scene reader's limits).
    const long long w = (long long)dw.max.x - dw.min.x + 1;
    const long long hgt = (long long)dw.max.y - dw.min.y + 1;
    if (w < 1 || hgt < 1 || w > 16384 || hgt > 16384 || w * hgt > 4096LL * 4096LL)
      throw AccumulationError(path + ": header gives " + std::to_string(w) + " x " +
                              std::to_string(hgt) +
                              " pixels; an accumulation file is at most 4096 x 4096 (damaged?)");
    acc.width = int(w);
    acc.height = int(hgt);
    // The exact channels are 32-bit words; OpenEXR would convert a FLOAT or
    // HALF channel to UINT silently, and the doubles rebuilt from those
    // words would be wrong.
    for (const char* c : kExact)
      for (const char* part : {".hi", ".lo"}) {
        const Imf::Channel* ch = h.channels().findChannel(std::string(c) + part);
        if (!ch) throw AccumulationError(path + ": channel " + c + part + " missing");
        if (ch->type != Imf::UINT)
          throw AccumulationError(path + ": channel " + c + part + " is " +
                                  (ch->type == Imf::FLOAT ? "FLOAT" : "HALF") +
                                  ", not UINT (the words of a double); not written by whisker");
      }
    // A file cut short (a copy that did not finish, a full disk): its line
    // offsets point past its end. Told by the header pass too, before a
    // merge checks ranges.
    if (!file.isComplete())
      throw AccumulationError(path + ": cannot read as OpenEXR: the file is incomplete");
    if (!with_sums) return acc;
    const std::size_t pixels = std::size_t(acc.width) * acc.height;
    std::vector<std::uint32_t> words[4];
    Imf::FrameBuffer fb;
    const std::size_t wx = 2 * sizeof(std::uint32_t), wy = wx * acc.width;
    const std::ptrdiff_t origin = (std::ptrdiff_t(dw.min.y) * acc.width + dw.min.x) * std::ptrdiff_t(wx);
    for (int c = 0; c < 4; ++c) {
      for (const char* part : {".hi", ".lo"})
        if (!h.channels().findChannel(std::string(kExact[c]) + part))
          throw AccumulationError(path + ": channel " + kExact[c] + part + " missing");
      words[c].assign(pixels * 2, 0);
      char* w = reinterpret_cast<char*>(words[c].data()) - origin;
      fb.insert(std::string(kExact[c]) + ".hi", Imf::Slice(Imf::UINT, w, wx, wy));
      fb.insert(std::string(kExact[c]) + ".lo", Imf::Slice(Imf::UINT, w + sizeof(std::uint32_t), wx, wy));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    acc.sum.resize(pixels * 3);
    acc.sum_sq.resize(pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
      for (int c = 0; c < 3; ++c) acc.sum[3 * p + c] = join_bits(words[c][2 * p], words[c][2 * p + 1]);
      acc.sum_sq[p] = join_bits(words[3][2 * p], words[3][2 * p + 1]);
      // Sums of radiance and of squares are finite and >= 0 (the renderer
      // drops NaN and infinite samples, and counts them in nan_count): any
      // other value is damage, and would spread NaN through a merge or a resume.
      for (int c = 0; c < 4; ++c) {
        const double v = c < 3 ? acc.sum[3 * p + c] : acc.sum_sq[p];
        if (std::isfinite(v) && v >= 0.0) continue;
        char where[64];
        std::snprintf(where, sizeof where, " of pixel (%zu, %zu) is ", p % std::size_t(acc.width),
                      p / std::size_t(acc.width));
        throw AccumulationError(path + ": " + kExact[c] + where + text(v) +
                                "; a part holds finite sums >= 0 (damaged?)");
      }
    }
    return acc;
  } catch (const AccumulationError&) {
    throw;
  } catch (const std::exception& e) {
    throw AccumulationError(path + ": cannot read as OpenEXR: " + e.what());
  }
}

}  // namespace

Accumulation read_accumulation(const std::string& path) { return read(path, true); }

Accumulation read_accumulation_header(const std::string& path) { return read(path, false); }

#else

void write_accumulation(const std::string& path, const Accumulation&) {
  throw ImageError(path + ": this build has no OpenEXR; accumulation files need it");
}

Accumulation read_accumulation(const std::string& path) {
  throw AccumulationError(path + ": this build has no OpenEXR; accumulation files need it");
}

Accumulation read_accumulation_header(const std::string& path) { return read_accumulation(path); }

#endif

}  // namespace whisker
