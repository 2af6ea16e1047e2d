#include "render/accumulation_io.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>

#include "render/image_io.h"

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
      attr("passes", std::to_string(acc.passes));
      attr("nan_count", std::to_string(acc.nan_count));
      attr("rays", std::to_string(acc.rays));
      attr("seconds", text(acc.seconds));
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

std::uint64_t count_attribute(const Imf::Header& h, const std::string& path, const char* name) {
  const std::string v = attribute(h, path, name);
  std::uint64_t n = 0;
  for (char c : v) {
    if (c < '0' || c > '9') throw AccumulationError(path + ": whisker." + name + " \"" + v + "\" is not a count");
    n = n * 10 + std::uint64_t(c - '0');
  }
  return n;
}

}  // namespace

Accumulation read_accumulation(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw AccumulationError(path + ": no such file");
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
    acc.passes = count_attribute(h, path, "passes");
    acc.nan_count = count_attribute(h, path, "nan_count");
    acc.rays = count_attribute(h, path, "rays");
    acc.seconds = std::strtod(attribute(h, path, "seconds").c_str(), nullptr);
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
    }
    return acc;
  } catch (const AccumulationError&) {
    throw;
  } catch (const std::exception& e) {
    throw AccumulationError(path + ": cannot read as OpenEXR: " + e.what());
  }
}

#else

void write_accumulation(const std::string& path, const Accumulation&) {
  throw ImageError(path + ": this build has no OpenEXR; accumulation files need it");
}

Accumulation read_accumulation(const std::string& path) {
  throw AccumulationError(path + ": this build has no OpenEXR; accumulation files need it");
}

#endif

}  // namespace whisker
