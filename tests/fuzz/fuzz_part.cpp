// libFuzzer harness for the part (accumulation EXR) reader: the input is
// written to a file and read, headers only and whole. A clean refusal
// (AccumulationError) is fine; any other exception, a crash, a sanitizer
// report or a part that breaks what merge and resume rely on is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>

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
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = whisker_fuzz::write_scratch("input.exr", reinterpret_cast<const char*>(data), size);
  try {
    check(whisker::read_accumulation_header(path.string()), false);
  } catch (const whisker::AccumulationError&) {
  }
  try {
    check(whisker::read_accumulation(path.string()), true);
  } catch (const whisker::AccumulationError&) {
  }
  return 0;
}
