#include "io/part_layers.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>

namespace whisker {

namespace {

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

// The doubles of a pixel in a band's order, and what each may hold: a
// signed one (a normal's sum) only finite values, the others finite values
// >= 0; `whole` is the double an odd half's sum may not exceed (-1: none).
struct DoubleLayer {
  const char* name;
  bool may_be_negative;
  int whole;
};
constexpr DoubleLayer kDoubles[] = {
    {"sum.R", false, -1},
    {"sum.G", false, -1},
    {"sum.B", false, -1},
    {"sumsq.Y", false, -1},
    // Snapshot::odd_rgb, then Snapshot::features (kFeatureSums of them).
    {"odd.sum.R", false, 0},
    {"odd.sum.G", false, 1},
    {"odd.sum.B", false, 2},
    {"feature.albedo.R", false, -1},
    {"feature.albedo.G", false, -1},
    {"feature.albedo.B", false, -1},
    {"feature.normal.X", true, -1},
    {"feature.normal.Y", true, -1},
    {"feature.normal.Z", true, -1},
    {"feature.depth.Z", false, -1},
    {"feature.odd.albedo.R", false, 7},
    {"feature.odd.albedo.G", false, 8},
    {"feature.odd.albedo.B", false, 9},
    {"feature.odd.normal.X", true, -1},
    {"feature.odd.normal.Y", true, -1},
    {"feature.odd.normal.Z", true, -1},
    {"feature.odd.depth.Z", false, 13},
};
constexpr std::size_t kBaseDoubles = 4;
constexpr std::size_t kAllDoubles = std::size(kDoubles);
static_assert(kAllDoubles == kBaseDoubles + 3 + kFeatureSums, "a layer for every feature sum");

// What is wrong with double `d` of a pixel whose doubles are `v`, or "".
std::string value_problem(const double* v, std::size_t d) {
  const DoubleLayer& l = kDoubles[d];
  if (l.may_be_negative ? !std::isfinite(v[d]) : !(std::isfinite(v[d]) && v[d] >= 0.0))
    return l.may_be_negative ? "; a part holds finite sums" : "; a part holds finite sums >= 0";
  // The sums of nonnegative values in one order: a half never exceeds the
  // whole (rounding is monotonic), so the even half is >= 0 too.
  if (l.whole >= 0 && v[d] > v[l.whole])
    return ", past " + std::string(kDoubles[l.whole].name) + " " + exact_text(v[l.whole]) +
           " (the odd samples' sum exceeds every sample's)";
  return {};
}

}  // namespace

std::string exact_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

PartLayout::PartLayout(bool features) {
  channels = {"R", "G", "B"};
  const std::size_t doubles = features ? kAllDoubles : kBaseDoubles;
  for (std::size_t d = 0; d < doubles; ++d) {
    channels.push_back(std::string(kDoubles[d].name) + ".hi");
    channels.push_back(std::string(kDoubles[d].name) + ".lo");
  }
}

void fill_band(const Accumulation& acc, const PartLayout& layout, int y0, int rows,
               std::vector<std::uint32_t>& band) {
  // The mean as mean_image computes it.
  const float inv = acc.samples() ? 1.0f / float(acc.samples()) : 0.0f;
  const std::size_t first = std::size_t(y0) * acc.width, pixels = std::size_t(rows) * acc.width;
  const std::size_t words = layout.words(), doubles = (words - PartLayout::kMeanWords) / 2;
  band.resize(pixels * words);
  double v[kAllDoubles];
  for (std::size_t p = 0; p < pixels; ++p) {
    const std::size_t px = first + p;
    for (int c = 0; c < 3; ++c) v[c] = acc.sum[3 * px + c];
    v[3] = acc.sum_sq[px];
    if (doubles == kAllDoubles) {
      for (int c = 0; c < 3; ++c) v[kBaseDoubles + c] = acc.odd_rgb[3 * px + c];
      for (int k = 0; k < kFeatureSums; ++k) v[kBaseDoubles + 3 + k] = acc.features[kFeatureSums * px + k];
    }
    std::uint32_t* w = &band[p * words];
    for (int c = 0; c < 3; ++c) {
      const float mean = float(v[c]) * inv;
      std::memcpy(&w[c], &mean, sizeof mean);
    }
    for (std::size_t d = 0; d < doubles; ++d)
      split_bits(v[d], w[PartLayout::kMeanWords + 2 * d], w[PartLayout::kMeanWords + 2 * d + 1]);
  }
}

SumsBand BandDoubles::view(std::size_t first) const {
  const bool has = !features.empty();
  return {first, sum_sq.size(), sum.data(), sum_sq.data(), has ? odd_rgb.data() : nullptr,
          has ? features.data() : nullptr};
}

std::string decode_band(const std::vector<std::uint32_t>& words, const PartLayout& layout,
                        std::size_t pixels, int width, int y0, BandDoubles& out) {
  const std::size_t stride = layout.words(), doubles = (stride - PartLayout::kMeanWords) / 2;
  const bool features = doubles == kAllDoubles;
  out.sum.resize(pixels * 3);
  out.sum_sq.resize(pixels);
  out.odd_rgb.resize(features ? pixels * 3 : 0);
  out.features.resize(features ? pixels * kFeatureSums : 0);
  double v[kAllDoubles];
  for (std::size_t p = 0; p < pixels; ++p) {
    const std::uint32_t* w = &words[p * stride + PartLayout::kMeanWords];
    for (std::size_t d = 0; d < doubles; ++d) v[d] = join_bits(w[2 * d], w[2 * d + 1]);
    // Checked before a merge or a resume adds them: a NaN or a negative
    // sum would spread through every later sum of the pixel.
    for (std::size_t d = 0; d < doubles; ++d) {
      const std::string why = value_problem(v, d);
      if (why.empty()) continue;
      char where[64];
      std::snprintf(where, sizeof where, " of pixel (%zu, %zu) is ", p % std::size_t(width),
                    std::size_t(y0) + p / std::size_t(width));
      return kDoubles[d].name + std::string(where) + exact_text(v[d]) + why + " (damaged?)";
    }
    for (int c = 0; c < 3; ++c) out.sum[3 * p + c] = v[c];
    out.sum_sq[p] = v[3];
    if (!features) continue;
    for (int c = 0; c < 3; ++c) out.odd_rgb[3 * p + c] = v[kBaseDoubles + c];
    for (int k = 0; k < kFeatureSums; ++k) out.features[kFeatureSums * p + k] = v[kBaseDoubles + 3 + k];
  }
  return {};
}

}  // namespace whisker
