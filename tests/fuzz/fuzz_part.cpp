// libFuzzer harness for the part (accumulation EXR) reader: the input is
// written to a file and read, headers only, whole, and merged on its own. A
// clean refusal (AccumulationError) is fine; any other exception, a crash, a
// sanitizer report or a part that breaks what merge and resume rely on is a
// finding.
//
// A part's checksums (whisker.checksum) refuse nearly every mutation, so
// that the checks behind them would never be reached: an input refused for
// a checksum that does not match is read again with the checksum the
// reader computed put in its place (the header's, then the pixels'). Each
// input is thus read as damaged and as if its writer had written it.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_common.h"
#include "io/accumulation_io.h"

namespace {

// What plan_merge, add_sums and a resumed film rely on.
void check(const whisker::Accumulation& a, bool with_sums) {
  if (a.width < 1 || a.height < 1 || a.width > 16384 || a.height > 16384) __builtin_trap();
  if (a.ranges.empty()) __builtin_trap();
  for (std::size_t i = 0; i < a.ranges.size(); ++i) {
    if (a.ranges[i].begin >= a.ranges[i].end) __builtin_trap();
    if (i > 0 && a.ranges[i].begin < a.ranges[i - 1].end) __builtin_trap();
  }
  if (!std::isfinite(a.counters.seconds) || a.counters.seconds < 0) __builtin_trap();
  if (!with_sums) return;
  const std::size_t pixels = std::size_t(a.width) * std::size_t(a.height);
  if (a.sum.size() != pixels * 3 || a.sum_sq.size() != pixels) __builtin_trap();
  for (const double v : a.sum)
    if (!std::isfinite(v) || v < 0) __builtin_trap();
  for (const double v : a.sum_sq)
    if (!std::isfinite(v) || v < 0) __builtin_trap();
  // Feature sums: all of them or none, each finite (part_layers.h).
  const bool features = a.odd_rgb.size() == pixels * 3 && a.features.size() == pixels * whisker::kFeatureSums;
  if (features != a.with_features || (!features && (!a.odd_rgb.empty() || !a.features.empty()))) __builtin_trap();
  for (std::size_t k = 0; k < a.odd_rgb.size(); ++k)
    if (!std::isfinite(a.odd_rgb[k]) || a.odd_rgb[k] < 0 || a.odd_rgb[k] > a.sum[k]) __builtin_trap();
  for (const double v : a.features)
    if (!std::isfinite(v)) __builtin_trap();
}

// Puts the CRC a checksum refusal names ("... does not match its checksum
// (crc32 1a2b3c4d, whisker.checksum says ...)") into whisker.checksum's
// value in `bytes`; false if the refusal is another one, or the attribute
// is not where a writer puts it.
bool reseal(std::string& bytes, const std::string& refusal) {
  const std::size_t at = refusal.find("does not match its checksum (crc32 ");
  if (at == std::string::npos) return false;
  const std::string crc = refusal.substr(at + 35, 8);
  const std::size_t field = refusal.find("its header does not match") != std::string::npos ? 13 : 29;
  const std::string tag("whisker.checksum\0string\0", 24);
  const std::size_t t = bytes.find(tag);
  if (crc.size() != 8 || t == std::string::npos || t + tag.size() + 4 + 37 > bytes.size()) return false;
  const std::size_t value = t + tag.size() + 4;  // after the value's 4-byte size
  if (bytes.compare(value + field, 8, crc) == 0) return false;
  bytes.replace(value + field, 8, crc);
  return true;
}

bool same_doubles(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

bool same_sums(const whisker::Accumulation& a, const whisker::Accumulation& b) {
  return same_doubles(a.sum, b.sum) && same_doubles(a.sum_sq, b.sum_sq) && same_doubles(a.odd_rgb, b.odd_rgb) &&
         same_doubles(a.features, b.features);
}

// Reads the part at `path` every way; returns the last refusal ("" if none).
std::string read_every_way(const std::string& path) {
  std::string refusal;
  try {
    check(whisker::read_accumulation_header(path), false);
  } catch (const whisker::AccumulationError& e) {
    refusal = e.what();
  }
  whisker::Accumulation whole;
  try {
    whole = whisker::read_accumulation(path);
    check(whole, true);
  } catch (const whisker::AccumulationError& e) {
    refusal = e.what();
  }
  try {
    // Bands of 2 rows: a merge reads a part band by band into its sums.
    const whisker::Accumulation merged = whisker::merge_accumulation_files({path}, {}, 2);
    check(merged, true);
    if (!same_sums(merged, whole)) __builtin_trap();  // one part merges to itself
  } catch (const whisker::AccumulationError& e) {
    refusal = e.what();
  }
  return refusal;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  // As given; then resealed (the header's checksum, then the pixels').
  for (int pass = 0; pass < 3; ++pass) {
    const auto path = whisker_fuzz::write_scratch("input.exr", bytes.data(), bytes.size());
    if (!reseal(bytes, read_every_way(path.string()))) break;
  }
  return 0;
}
