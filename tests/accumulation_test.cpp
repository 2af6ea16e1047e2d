// Accumulations (src/render/accumulation): the counters a render carries
// beside its sums, and how parts and snapshots hand both on.
#include <gtest/gtest.h>

#include "render/accumulation.h"

namespace whisker {
namespace {

Accumulation part(SampleRange range, RenderCounters counters) {
  Accumulation a;
  a.width = 2;
  a.height = 1;
  a.sum = {1, 2, 3, 4, 5, 6};
  a.sum_sq = {1, 2};
  a.ranges = {range};
  a.counters = counters;
  a.id = {"room", "0123456789abcdef", R"({"seed":1})"};
  return a;
}

TEST(RenderCounters, MergingAddsEveryField) {
  RenderCounters a{.passes = 2, .nan_count = 3, .rays = 1ull << 40, .seconds = 1.5};
  a += {.passes = 5, .nan_count = 0, .rays = 7, .seconds = 0.25};
  EXPECT_EQ(a.passes, 7u);
  EXPECT_EQ(a.nan_count, 3u);
  EXPECT_EQ(a.rays, (1ull << 40) + 7);
  EXPECT_EQ(a.seconds, 1.75);
  // Adding nothing changes nothing.
  const RenderCounters before = a;
  a += RenderCounters{};
  EXPECT_EQ(a, before);
}

TEST(RenderCounters, AMergeSumsThePartsCounters) {
  // Given out of sample order: the counters are the sums all the same.
  std::vector<NamedAccumulation> parts = {
      {"b.exr", part({4, 8}, {.passes = 1, .nan_count = 2, .rays = 100, .seconds = 0.5})},
      {"a.exr", part({0, 4}, {.passes = 3, .nan_count = 0, .rays = 50, .seconds = 2.0})},
  };
  const Accumulation merged = merge_accumulations(parts);
  EXPECT_EQ(merged.counters, (RenderCounters{.passes = 4, .nan_count = 2, .rays = 150, .seconds = 2.5}));
  EXPECT_EQ(merged.ranges, (std::vector<SampleRange>{{0, 8}}));
}

TEST(RenderCounters, SnapshotsAndAccumulationsHandThemOnWhole) {
  const RenderCounters c{.passes = 3, .nan_count = 5, .rays = 1ull << 40, .seconds = 12.25};
  const Accumulation a = part({16, 20}, c);
  const Snapshot s = snapshot_of(a);
  EXPECT_EQ(s.counters, c);
  const Accumulation back = accumulation_of(s, 16, a.id);
  EXPECT_EQ(back.counters, c);
  EXPECT_EQ(back.ranges, a.ranges);
  // The sums go through the snapshot exactly, so a checkpoint of a resumed
  // render writes what it read.
  EXPECT_EQ(back.sum, a.sum);
  EXPECT_EQ(back.sum_sq, a.sum_sq);
}

}  // namespace
}  // namespace whisker
