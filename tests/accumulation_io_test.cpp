// The accumulation file format (io/accumulation_io.h) on its own: damaged
// sums and counters refused naming the field, a round trip that keeps every
// bit and the header, and the sample ranges' text and gaps.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "io/accumulation_io.h"
#include "same_bits.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace whisker;

TEST(AccumulationFile, DamagedSumsAndCountersAreRefusedNamingTheField) {
  Accumulation a;
  a.width = 2;
  a.height = 1;
  a.sum = {1, 2, 3, 4, 5, 6};
  a.sum_sq = {1, 2};
  a.ranges = {{0, 4}};
  a.counters.passes = 1;
  a.id = {"room", "0123456789abcdef", R"({"seed":1})", estimator_identity()};
  const TempDir temp("bad-part");
  const fs::path p = temp.path() / "bad.exr";
  const auto refusal = [&](const Accumulation& bad) {
    write_accumulation(p.string(), bad);
    try {
      read_accumulation(p.string());
    } catch (const AccumulationError& e) {
      return std::string(e.what());
    }
    return std::string("(read)");
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double v : {nan, inf, -inf, -1.0}) {
    Accumulation b = a;
    b.sum[4] = v;  // G of pixel (1, 0)
    EXPECT_NE(refusal(b).find("sum.G of pixel (1, 0)"), std::string::npos) << refusal(b);
    b = a;
    b.sum_sq[0] = v;
    EXPECT_NE(refusal(b).find("sumsq.Y of pixel (0, 0)"), std::string::npos) << refusal(b);
  }
  Accumulation b = a;
  b.counters.seconds = nan;
  EXPECT_NE(refusal(b).find("whisker.seconds \"nan\""), std::string::npos) << refusal(b);
  b.counters.seconds = -2;
  EXPECT_NE(refusal(b).find("whisker.seconds \"-2\""), std::string::npos) << refusal(b);
  EXPECT_EQ(refusal(a), "(read)");
  std::vector<SampleRange> r;
  for (const char* bad : {"0:5,", "0:5,,6:7", ",0:5", "0:5, 6:7"}) EXPECT_FALSE(parse_ranges(bad, r)) << bad;
  EXPECT_TRUE(parse_ranges("0:5,6:7", r));
}

TEST(AccumulationFile, RoundTripKeepsEveryBitAndTheHeader) {
  Accumulation a;
  a.width = 3;
  a.height = 2;
  const double special[] = {0.0, 0.1, 1.0 / 3.0, 1e300, std::numeric_limits<double>::denorm_min(),
                            std::nextafter(1.0, 2.0), 123456789.123456789, 2e-310};
  for (int k = 0; k < 18; ++k) a.sum.push_back(special[k % 8] * (k + 1));
  for (int k = 0; k < 6; ++k) a.sum_sq.push_back(special[(k + 3) % 8]);
  a.ranges = {{0, 512}, {1024, 2048}};
  a.counters.passes = 3;
  a.counters.nan_count = 5;
  a.counters.rays = 1ull << 40;
  a.counters.seconds = 12.25;
  a.id = {"room", "0123456789abcdef", R"({"seed":1})", estimator_identity()};
  const TempDir temp("part");
  const std::string p = temp.file("acc.exr");
  write_accumulation(p, a);
  const Accumulation b = read_accumulation(p);
  EXPECT_EQ(b.width, 3);
  EXPECT_EQ(b.height, 2);
  EXPECT_TRUE(same_bits(a.sum, b.sum));
  EXPECT_TRUE(same_bits(a.sum_sq, b.sum_sq));
  EXPECT_EQ(b.ranges, a.ranges);
  EXPECT_EQ(b.counters.passes, 3u);
  EXPECT_EQ(b.counters.nan_count, 5u);
  EXPECT_EQ(b.counters.rays, 1ull << 40);
  EXPECT_EQ(b.counters.seconds, 12.25);
  EXPECT_EQ(b.id.scene, "room");
  EXPECT_EQ(b.id.scene_hash, "0123456789abcdef");
  EXPECT_EQ(b.id.settings, R"({"seed":1})");
  EXPECT_EQ(b.id.estimator, estimator_identity());
  EXPECT_EQ(b.samples(), 512u + 1024u);
}

TEST(AccumulationFile, MissingRangesAreTheGapsFromZero) {
  EXPECT_TRUE(missing_ranges({{0, 4}, {4, 8}}).empty());
  EXPECT_EQ(missing_ranges({{2, 4}, {6, 8}}), (std::vector<SampleRange>{{0, 2}, {4, 6}}));
  SampleRange r;
  EXPECT_TRUE(parse_sample_range("512:1024", r));
  EXPECT_EQ(r, (SampleRange{512, 1024}));
  for (const char* bad : {"", "5", "5:5", "6:5", "a:b", "1:2:3", "-1:4"})
    EXPECT_FALSE(parse_sample_range(bad, r)) << bad;
}
