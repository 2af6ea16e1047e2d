// A part's feature layers (the denoiser's feature sums and the odd samples'
// RGB, io/part_layers.h): kept bit for bit, folded by a merge as the
// radiance is, and refused in one line naming the file and the layer when
// they cannot be a render's: a value no render sums (NaN, a negative albedo
// or depth, an odd half larger than the whole), a half or layer missing, a
// layer of the wrong type, layers that say they hold other samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "io/accumulation_io.h"
#include "run_whisker.h"
#include "same_bits.h"
#include "temp_dir.h"
#include "test_random.h"

namespace fs = std::filesystem;
using namespace whisker;

namespace {

// A part of w x h pixels with features, its values varied and possible: the
// odd halves below their wholes, normals of either sign.
Accumulation part_with_features(int w, int h, SampleRange range, unsigned seed) {
  Accumulation a;
  a.width = w;
  a.height = h;
  TestRandom random(seed);
  const auto next = [&] { return random.next(); };
  const std::size_t pixels = std::size_t(w) * std::size_t(h);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (int c = 0; c < 3; ++c) a.sum.push_back(next() * 40.0);
    for (int c = 0; c < 3; ++c) a.odd_rgb.push_back(a.sum[3 * p + c] * next());
    a.sum_sq.push_back(next() * 900.0);
    double f[kFeatureSums];
    for (int c = 0; c < 3; ++c) {
      f[c] = next() * 4.0;            // albedo
      f[3 + c] = next() * 8.0 - 4.0;  // normal
    }
    f[6] = next() * 1e3;  // depth
    for (int k = 0; k < 7; ++k) f[7 + k] = k >= 3 && k < 6 ? next() * 4.0 - 2.0 : f[k] * next();
    a.features.insert(a.features.end(), f, f + kFeatureSums);
  }
  a.with_features = true;
  a.ranges = {range};
  a.counters = {.passes = 1, .nan_count = 0, .rays = 1000, .seconds = 0.5};
  a.id = {"room", "0123456789abcdef", R"({"aa":true,"seed":0})", estimator_identity()};
  return a;
}

// The bytes of `file` with the first `from` replaced by `to` (same length).
std::string replaced(const std::string& file, const std::string& from, const std::string& to) {
  std::string d = file_bytes(file);
  const std::size_t at = d.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) d.replace(at, from.size(), to);
  return d;
}

// What reading `path` (as a resume does) says, or "(read)".
std::string refusal(const std::string& path) {
  try {
    read_accumulation(path);
  } catch (const AccumulationError& e) {
    return e.what();
  }
  return "(read)";
}

}  // namespace

TEST(PartFeatures, KeptBitForBitAndMergedInRangeOrder) {
  const TempDir temp("features");
  const Accumulation a = part_with_features(5, 37, {0, 4}, 1), b = part_with_features(5, 37, {4, 8}, 2);
  write_accumulation(temp.file("a.exr"), a);
  write_accumulation(temp.file("b.exr"), b);
  const Accumulation back = read_accumulation(temp.file("a.exr"), 7);
  EXPECT_TRUE(back.with_features);
  EXPECT_TRUE(same_bits(back.features, a.features));
  EXPECT_TRUE(same_bits(back.odd_rgb, a.odd_rgb));
  EXPECT_TRUE(same_bits(back.sum, a.sum));
  EXPECT_TRUE(read_accumulation_header(temp.file("a.exr")).with_features);
  // Band by band (of any height) the merge adds what the whole parts add.
  const Accumulation whole = merge_accumulations({{"a", a}, {"b", b}});
  for (const int band : {1, 5, 37, 64}) {
    const Accumulation m = merge_accumulation_files({temp.file("b.exr"), temp.file("a.exr")}, {}, band);
    ASSERT_TRUE(m.with_features);
    EXPECT_TRUE(same_bits(m.features, whole.features)) << band;
    EXPECT_TRUE(same_bits(m.odd_rgb, whole.odd_rgb)) << band;
  }
  // The fold: a's sums, then b's, from zero.
  EXPECT_EQ(whole.features[13], (0.0 + a.features[13]) + b.features[13]);
  // A part without features beside it: the merge keeps none, and says which.
  Accumulation plain = part_with_features(5, 37, {8, 12}, 3);
  plain.with_features = false;
  write_accumulation(temp.file("plain.exr"), plain);
  std::string dropped;
  const Accumulation m =
      merge_accumulation_files({temp.file("a.exr"), temp.file("plain.exr")}, {}, kBandRows, &dropped);
  EXPECT_FALSE(m.with_features);
  EXPECT_TRUE(m.features.empty());
  EXPECT_EQ(dropped, temp.file("plain.exr") + " keeps no feature buffers (" + temp.file("a.exr") + " does)");
  // Written without features, a part's file is what it always was: no layer, no attribute.
  const std::string bytes = file_bytes(temp.file("plain.exr"));
  EXPECT_EQ(bytes.find("feature."), std::string::npos);
  EXPECT_EQ(bytes.find("whisker.features"), std::string::npos);
}

TEST(PartFeatures, ImpossibleValuesAreRefusedNamingTheLayerAndPixel) {
  const TempDir temp("feature-values");
  const Accumulation good = part_with_features(3, 2, {0, 4}, 4);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    int feature;  // index in a pixel's features, or -1 - c for odd_rgb channel c
    double value;
    std::string message;
  };
  // Pixel (1, 1) is pixel 4.
  const Case cases[] = {
      {1, -1.0, "feature.albedo.G of pixel (1, 1) is -1; a part holds finite sums >= 0 (damaged?)"},
      {6, nan, "feature.depth.Z of pixel (1, 1) is nan; a part holds finite sums >= 0"},
      {4, inf, "feature.normal.Y of pixel (1, 1) is inf; a part holds finite sums (damaged?)"},
      {13, -0.5, "feature.odd.depth.Z of pixel (1, 1) is -0.5"},
      {7, 1e6, "feature.odd.albedo.R of pixel (1, 1) is 1000000, past feature.albedo.R "},
      {-3, 1e6, "odd.sum.B of pixel (1, 1) is 1000000, past sum.B "},
      {-1, nan, "odd.sum.R of pixel (1, 1) is nan"},
  };
  for (const Case& c : cases) {
    Accumulation bad = good;
    if (c.feature >= 0)
      bad.features[4 * kFeatureSums + std::size_t(c.feature)] = c.value;
    else
      bad.odd_rgb[4 * 3 + std::size_t(-1 - c.feature)] = c.value;
    const std::string path = temp.file("bad.exr");
    write_accumulation(path, bad);
    const std::string why = refusal(path);
    EXPECT_EQ(why.find(path + ": " + c.message), 0u) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;
    try {
      merge_accumulation_files({path});
      ADD_FAILURE() << "merged: " << c.message;
    } catch (const AccumulationError& e) {
      EXPECT_EQ(std::string(e.what()), why);
    }
  }
}

TEST(PartFeatures, AMissingHalfAWrongLayerOrOtherSamplesAreRefused) {
  const TempDir temp("feature-layers");
  const std::string good = temp.file("good.exr"), bad = temp.file("bad.exr");
  write_accumulation(good, part_with_features(4, 3, {0, 4}, 5));
  const auto refused = [&](const std::string& from, const std::string& to) {
    std::ofstream(bad, std::ios::binary | std::ios::trunc) << replaced(good, from, to);
    return refusal(bad);
  };
  EXPECT_EQ(refusal(good), "(read)");
  // The odd half of the depth gone (its .lo word renamed).
  EXPECT_EQ(refused(std::string("feature.odd.depth.Z.lo\0", 23), std::string("feature.odd.depth.Z.xx\0", 23)),
            bad + ": channel feature.odd.depth.Z.lo missing (whisker.features says the part has every "
                  "feature layer)");
  // A layer stored as FLOAT (pixel type 2): OpenEXR would convert it.
  EXPECT_EQ(refused(std::string("feature.albedo.R.hi\0\0\0\0\0", 24), std::string("feature.albedo.R.hi\0\2\0\0\0", 24)),
            bad + ": channel feature.albedo.R.hi is FLOAT, not UINT (the words of a double); not written by whisker");
  // Layers that say they sum other samples than the part's (0:3 of 0:4).
  EXPECT_EQ(refused(std::string("whisker.features\0string\0\3\0\0\0000:4", 31),
                    std::string("whisker.features\0string\0\3\0\0\0000:3", 31)),
            bad + ": whisker.features \"0:3\": the feature layers hold other samples than the part's 0:4 "
                  "(whisker.samples)");
  // Layers without the attribute that says which samples they hold.
  EXPECT_EQ(refused("whisker.features", "whisker.featurez"),
            bad + ": channel odd.sum.R.hi without whisker.features (the samples the feature layers hold); "
                  "not written by whisker");
}

// Through the binary: exit 2 and one line naming the file and the layer,
// for a merge and for a resume, and nothing written.
TEST(PartFeatures, TheBinaryRefusesBadFeatureLayersInOneLine) {
  const TempDir temp("feature-cli");
  Accumulation bad = part_with_features(4, 3, {0, 4}, 6);
  bad.features[2] = -2.0;  // albedo B of pixel (0, 0)
  write_accumulation(temp.file("bad.exr"), bad);
  for (const std::string& args : {"merge " + temp.file("bad.exr") + " --out " + temp.file("m.png"),
                                 "--headless --quiet --scene three-balls --frames 2 --resume " +
                                     temp.file("bad.exr") + " --out-sum " + temp.file("r.exr")}) {
    const Result r = run(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(temp.file("bad.exr") + ": feature.albedo.B of pixel (0, 0) is -2"), std::string::npos)
        << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
  EXPECT_FALSE(fs::exists(temp.file("m.png")));
  EXPECT_FALSE(fs::exists(temp.file("r.exr")));
}
