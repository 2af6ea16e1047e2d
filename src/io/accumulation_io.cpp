#include "io/accumulation_io.h"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <exception>
#include <filesystem>
#include <iterator>
#include <memory>

#include "io/atomic_file.h"
#include "io/image_error.h"
#include "io/part_checks.h"
#include "io/part_layers.h"

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

// Format 2 added the estimator's identity and the checksums.
constexpr const char* kFormat = "whisker-accumulation 2";
constexpr const char* kOldFormat = "whisker-accumulation 1";

}  // namespace

#ifdef WHISKER_HAVE_OPENEXR

namespace {

// The checksum covers the words as EXR stores them (little-endian); the
// band buffers hold them in this machine's order, which is the same.
static_assert(std::endian::native == std::endian::little, "the part checksum assumes little-endian words");

// Whisker's own header attributes, in the order the header checksum covers them.
constexpr const char* kAttributes[] = {"format", "samples",   "scene", "scene_hash", "estimator",
                                       "settings", "passes", "nan_count", "rays", "seconds"};
constexpr std::size_t kAttributeCount = std::size(kAttributes);

std::vector<std::string> attribute_values(const Accumulation& acc) {
  return {kFormat,
          ranges_to_string(acc.ranges),
          acc.id.scene,
          acc.id.scene_hash,
          acc.id.estimator,
          acc.id.settings,
          std::to_string(acc.counters.passes),
          std::to_string(acc.counters.nan_count),
          std::to_string(acc.counters.rays),
          exact_text(acc.counters.seconds)};
}

// Slices of the band of rows from y0 (in the file's coordinates) at `band`.
Imf::FrameBuffer band_frame(std::vector<std::uint32_t>& band, const PartLayout& layout,
                            const Imath::Box2i& dw, int y0) {
  const std::size_t width = std::size_t(dw.max.x) - dw.min.x + 1;
  const std::size_t xs = layout.words() * sizeof(std::uint32_t), ys = xs * width;
  // OpenEXR addresses pixel (x, y) at base + x * xs + y * ys.
  char* base = reinterpret_cast<char*>(band.data()) - std::ptrdiff_t(dw.min.x) * std::ptrdiff_t(xs) -
               std::ptrdiff_t(y0) * std::ptrdiff_t(ys);
  Imf::FrameBuffer fb;
  for (std::size_t c = 0; c < layout.words(); ++c)
    fb.insert(layout.channels[c], Imf::Slice(layout.is_float(c) ? Imf::FLOAT : Imf::UINT,
                                             base + c * sizeof(std::uint32_t), xs, ys));
  return fb;
}

std::uint32_t band_crc(std::uint32_t crc, const std::vector<std::uint32_t>& band) {
  return crc32_of(crc, band.data(), band.size() * sizeof(band[0]));
}

// The attribute a part with feature layers has, and its value: the sample
// ranges those layers sum, as whisker.samples gives them.
constexpr const char* kFeaturesAttribute = "whisker.features";

// The CRC-32 of Whisker's attributes (name, NUL, value, NUL, in kAttributes'
// order, then whisker.features when the part has it) and of the data
// window the pixels are read in.
std::uint32_t header_crc(const std::vector<std::string>& values, const std::string& features,
                         const Imath::Box2i& dw) {
  std::string all;
  for (std::size_t i = 0; i < kAttributeCount; ++i)
    ((all += "whisker.") += kAttributes[i]).append(1, '\0').append(values[i]).append(1, '\0');
  if (!features.empty()) (all += kFeaturesAttribute).append(1, '\0').append(features).append(1, '\0');
  all += "dataWindow " + std::to_string(dw.min.x) + " " + std::to_string(dw.min.y) + " " +
         std::to_string(dw.max.x) + " " + std::to_string(dw.max.y);
  return crc32_of(0, all.data(), all.size());
}

}  // namespace

void write_accumulation(const std::string& path, const Accumulation& acc, int band_rows) {
  const std::size_t pixels = std::size_t(acc.width) * acc.height;
  if (acc.width <= 0 || acc.height <= 0 || acc.sum.size() != pixels * 3 ||
      acc.sum_sq.size() != pixels ||
      (acc.with_features && (acc.odd_rgb.size() != pixels * 3 || acc.features.size() != pixels * kFeatureSums)))
    throw ImageError(path + ": empty or malformed accumulation");
  band_rows = std::max(band_rows, 1);
  const std::vector<std::string> values = attribute_values(acc);
  const std::string features = acc.with_features ? ranges_to_string(acc.ranges) : std::string();
  const PartLayout layout(acc.with_features);
  const Imath::Box2i dw({0, 0}, {acc.width - 1, acc.height - 1});
  // The header holds the pixels' checksum: one pass over the bands for it,
  // one to write them (a band at a time, never a copy of the image).
  std::vector<std::uint32_t> band;
  std::uint32_t crc = 0;
  for (int y0 = 0; y0 < acc.height; y0 += band_rows) {
    fill_band(acc, layout, y0, std::min(band_rows, acc.height - y0), band);
    crc = band_crc(crc, band);
  }
  write_file_atomically(path, [&](const std::string& tmp) {
    try {
      Imf::Header header(acc.width, acc.height);
      for (std::size_t c = 0; c < layout.words(); ++c)
        header.channels().insert(layout.channels[c], Imf::Channel(layout.is_float(c) ? Imf::FLOAT : Imf::UINT));
      for (std::size_t i = 0; i < kAttributeCount; ++i)
        header.insert(std::string("whisker.") + kAttributes[i], Imf::StringAttribute(values[i]));
      if (!features.empty()) header.insert(kFeaturesAttribute, Imf::StringAttribute(features));
      header.insert("whisker.checksum",
                    Imf::StringAttribute(checksum_text(header_crc(values, features, dw), crc)));
      Imf::OutputFile file(tmp.c_str(), header);
      for (int y0 = 0; y0 < acc.height; y0 += band_rows) {
        const int rows = std::min(band_rows, acc.height - y0);
        fill_band(acc, layout, y0, rows, band);
        file.setFrameBuffer(band_frame(band, layout, dw, y0));
        file.writePixels(rows);
      }
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
std::uint64_t count_attribute(const std::string& v, const std::string& path, const char* name) {
  std::uint64_t n = 0;
  const auto [end, err] = std::from_chars(v.data(), v.data() + v.size(), n);
  if (v.empty() || v[0] < '0' || v[0] > '9' || end != v.data() + v.size() || err != std::errc())
    throw AccumulationError(path + ": whisker." + name + " \"" + cut_value(v) +
                            "\" is not a count (decimal digits, below 2^64)");
  return n;
}

// Render seconds: a finite number >= 0, as the writer writes it.
double seconds_attribute(const std::string& v, const std::string& path) {
  double d = 0.0;
  const auto [end, err] = std::from_chars(v.data(), v.data() + v.size(), d);
  if (v.empty() || end != v.data() + v.size() || err != std::errc() || !std::isfinite(d) || d < 0)
    throw AccumulationError(path + ": whisker.seconds \"" + cut_value(v) +
                            "\" is not a finite number of seconds >= 0");
  return d;
}

// A part open for reading, its header checked: each of Whisker's fields,
// the size, the feature layers' samples and the word channels, then the
// attributes against the header checksum.
class PartFile {
 public:
  explicit PartFile(const std::string& path);
  // Reads the sums in bands of `band_rows` rows, then checks the pixel checksum.
  void read_sums(int band_rows, const SumBand& band);

  Accumulation acc;  // the header, sums empty
  std::string checksum;

 private:
  void parse(const std::vector<std::string>& values);
  void parse_features(const Imf::Header& h);
  void check_channels() const;

  std::string path_;
  std::string features_;  // whisker.features, "" without
  std::unique_ptr<Imf::InputFile> file_;
  Imath::Box2i dw_;
  std::uint32_t pixels_crc_ = 0;
};

PartFile::PartFile(const std::string& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw AccumulationError(path + ": no such file");
  check_header_sizes(path);
  file_ = std::make_unique<Imf::InputFile>(path.c_str());
  const Imf::Header& h = file_->header();
  const std::string format = attribute(h, path, "format");
  if (format == kOldFormat)
    throw AccumulationError(path + ": written by an older whisker (" + kOldFormat +
                            ", without checksums); render it again");
  if (format != kFormat)
    throw AccumulationError(path + ": unknown accumulation format \"" + cut_value(format) + "\" (expected " +
                            kFormat + ")");
  std::vector<std::string> values;
  for (const char* name : kAttributes) values.push_back(attribute(h, path, name));
  checksum = attribute(h, path, "checksum");
  std::uint32_t header = 0;
  if (!parse_checksum(checksum, header, pixels_crc_))
    throw AccumulationError(path + ": whisker.checksum \"" + cut_value(checksum) +
                            "\" is not \"crc32 header XXXXXXXX pixels XXXXXXXX\"");
  dw_ = h.dataWindow();
  // Each field as the writer writes it first, so that a value no writer
  // writes is named as such (the header checksum would refuse it too).
  parse(values);
  parse_features(h);
  check_channels();
  if (const std::uint32_t crc = header_crc(values, features_, dw_); crc != header)
    throw AccumulationError(path + ": damaged: its header does not match its checksum (crc32 " +
                            crc_text(crc) + ", whisker.checksum says " + crc_text(header) + ")");
  // A file cut short (a copy that did not finish, a full disk): its line
  // offsets point past its end. Told by the header pass too, before a
  // merge checks ranges.
  if (!file_->isComplete())
    throw AccumulationError(path + ": cannot read as OpenEXR: the file is incomplete");
}

void PartFile::parse(const std::vector<std::string>& values) {
  if (!parse_ranges(values[1], acc.ranges))
    throw AccumulationError(path_ + ": whisker.samples \"" + cut_value(values[1]) +
                            "\" is not a list of sorted ranges A:B");
  acc.id = {.scene = values[2], .scene_hash = values[3], .settings = values[5], .estimator = values[4]};
  acc.counters.passes = count_attribute(values[6], path_, "passes");
  acc.counters.nan_count = count_attribute(values[7], path_, "nan_count");
  acc.counters.rays = count_attribute(values[8], path_, "rays");
  acc.counters.seconds = seconds_attribute(values[9], path_);
  // The header's size is checked before the pixels are allocated: a 35 KB
  // file claiming 40000 x 40000 pixels asked for 51 GB. Renders are at
  // most 16384 pixels a side and 4096 x 4096 in all (the scene reader's limits).
  const long long w = (long long)dw_.max.x - dw_.min.x + 1;
  const long long hgt = (long long)dw_.max.y - dw_.min.y + 1;
  if (w < 1 || hgt < 1 || w > 16384 || hgt > 16384 || w * hgt > 4096LL * 4096LL)
    throw AccumulationError(path_ + ": header gives " + std::to_string(w) + " x " +
                            std::to_string(hgt) +
                            " pixels; an accumulation file is at most 4096 x 4096 (damaged?)");
  acc.width = int(w);
  acc.height = int(hgt);
}

void PartFile::parse_features(const Imf::Header& h) {
  // The feature layers sum the part's samples, no others: a mean of them
  // divides by the part's count (whisker.samples).
  const auto* a = h.findTypedAttribute<Imf::StringAttribute>(kFeaturesAttribute);
  if (!a) return;
  features_ = a->value();
  std::vector<SampleRange> ranges;
  if (!parse_ranges(features_, ranges) || ranges != acc.ranges)
    throw AccumulationError(path_ + ": " + kFeaturesAttribute + " \"" + cut_value(features_) +
                            "\": the feature layers hold other samples than the part's " +
                            ranges_to_string(acc.ranges) + " (whisker.samples)");
  acc.with_features = true;
}

void PartFile::check_channels() const {
  // The exact channels are 32-bit words; OpenEXR would convert a FLOAT or
  // HALF channel to UINT silently, and the doubles rebuilt from those
  // words would be wrong. The mean channels are FLOAT, as written.
  const PartLayout layout(acc.with_features);
  const Imf::ChannelList& list = file_->header().channels();
  for (std::size_t c = 0; c < layout.words(); ++c) {
    const std::string& name = layout.channels[c];
    const Imf::Channel* ch = list.findChannel(name);
    if (!ch)
      throw AccumulationError(path_ + ": channel " + name + " missing" +
                              (acc.with_features && c >= PartLayout(false).words()
                                   ? " (whisker.features says the part has every feature layer)"
                                   : ""));
    const Imf::PixelType want = layout.is_float(c) ? Imf::FLOAT : Imf::UINT;
    if (ch->type != want)
      throw AccumulationError(path_ + ": channel " + name + " is " +
                              (ch->type == Imf::FLOAT ? "FLOAT" : ch->type == Imf::HALF ? "HALF" : "UINT") +
                              ", not " + (layout.is_float(c) ? "FLOAT" : "UINT (the words of a double)") +
                              "; not written by whisker");
    if (ch->xSampling != 1 || ch->ySampling != 1)
      throw AccumulationError(path_ + ": channel " + name + " is subsampled; not written by whisker");
  }
  if (acc.with_features) return;
  // Feature layers without the attribute that says which samples they sum.
  for (const std::string& name : PartLayout(true).channels)
    if (list.findChannel(name) && std::find(layout.channels.begin(), layout.channels.end(), name) ==
                                      layout.channels.end())
      throw AccumulationError(path_ + ": channel " + name + " without " + kFeaturesAttribute +
                              " (the samples the feature layers hold); not written by whisker");
}

void PartFile::read_sums(int band_rows, const SumBand& band) {
  band_rows = std::max(band_rows, 1);
  const PartLayout layout(acc.with_features);
  std::vector<std::uint32_t> words;
  BandDoubles doubles;
  std::uint32_t crc = 0;
  for (int y0 = 0; y0 < acc.height; y0 += band_rows) {
    const int rows = std::min(band_rows, acc.height - y0);
    const std::size_t pixels = std::size_t(rows) * acc.width;
    words.assign(pixels * layout.words(), 0);
    file_->setFrameBuffer(band_frame(words, layout, dw_, dw_.min.y + y0));
    file_->readPixels(dw_.min.y + y0, dw_.min.y + y0 + rows - 1);
    crc = band_crc(crc, words);
    if (const std::string why = decode_band(words, layout, pixels, acc.width, y0, doubles); !why.empty())
      throw AccumulationError(path_ + ": " + why);
    band(doubles.view(std::size_t(y0) * acc.width));
  }
  if (crc != pixels_crc_)
    throw AccumulationError(path_ + ": damaged: its pixels do not match its checksum (crc32 " +
                            crc_text(crc) + ", whisker.checksum says " + crc_text(pixels_crc_) + ")");
}

// Runs f, telling OpenEXR's exceptions as AccumulationError naming the path.
template <class F>
auto guarded(const std::string& path, F f) {
  try {
    return f();
  } catch (const AccumulationError&) {
    throw;
  } catch (const std::exception& e) {
    throw AccumulationError(path + ": cannot read as OpenEXR: " + e.what());
  }
}

}  // namespace

Accumulation read_accumulation_bands(const std::string& path, int band_rows, const SumBand& band) {
  return guarded(path, [&] {
    PartFile part(path);
    part.read_sums(band_rows, band);
    return part.acc;
  });
}

Accumulation read_accumulation(const std::string& path, int band_rows) {
  return guarded(path, [&] {
    PartFile part(path);
    Accumulation& acc = part.acc;
    const std::size_t all = std::size_t(acc.width) * acc.height;
    acc.sum.resize(all * 3);
    acc.sum_sq.resize(all);
    acc.odd_rgb.resize(acc.with_features ? all * 3 : 0);
    acc.features.resize(acc.with_features ? all * kFeatureSums : 0);
    part.read_sums(band_rows, [&](const SumsBand& b) {
      const auto copy = [&](const double* from, std::vector<double>& to, std::size_t n) {
        if (from) std::copy(from, from + b.pixels * n, to.begin() + std::ptrdiff_t(b.first * n));
      };
      copy(b.sum, acc.sum, 3);
      copy(b.sum_sq, acc.sum_sq, 1);
      copy(b.odd_rgb, acc.odd_rgb, 3);
      copy(b.features, acc.features, kFeatureSums);
    });
    return std::move(acc);
  });
}

Accumulation read_accumulation_header(const std::string& path) {
  return guarded(path, [&] { return PartFile(path).acc; });
}

Accumulation merge_accumulation_files(const std::vector<std::string>& paths,
                                      const std::function<void(const Accumulation&)>& before_sums,
                                      int band_rows, std::string* features_dropped) {
  // Headers first, checked against each other; then each part's sums band
  // by band into the merged sums, in range order (the exactness rule).
  std::vector<NamedAccumulation> parts;
  std::vector<std::string> checksums;
  for (const std::string& p : paths) {
    guarded(p, [&] {
      PartFile part(p);
      parts.push_back({p, std::move(part.acc)});
      checksums.push_back(part.checksum);
      return 0;
    });
  }
  std::vector<std::size_t> order;
  Accumulation out = plan_merge(parts, order);
  if (features_dropped) *features_dropped = mixed_features(parts);
  if (before_sums) before_sums(out);
  for (const std::size_t i : order) {
    guarded(parts[i].name, [&] {
      PartFile part(parts[i].name);
      if (part.checksum != checksums[i])
        throw AccumulationError(parts[i].name + ": changed while the merge read it");
      part.read_sums(band_rows, [&](const SumsBand& b) { add_sums(out, b); });
      return 0;
    });
  }
  return out;
}

#else

void write_accumulation(const std::string& path, const Accumulation&, int) {
  throw ImageError(path + ": this build has no OpenEXR; accumulation files need it");
}

Accumulation read_accumulation_bands(const std::string& path, int, const SumBand&) {
  throw AccumulationError(path + ": this build has no OpenEXR; accumulation files need it");
}

Accumulation read_accumulation(const std::string& path, int) { return read_accumulation_bands(path, 0, {}); }

Accumulation read_accumulation_header(const std::string& path) { return read_accumulation(path, 0); }

Accumulation merge_accumulation_files(const std::vector<std::string>& paths,
                                      const std::function<void(const Accumulation&)>&, int, std::string*) {
  if (paths.empty()) throw AccumulationError("nothing to merge");
  return read_accumulation(paths[0], 0);
}

#endif

}  // namespace whisker
