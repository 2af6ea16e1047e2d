// Sample indices far from 0: split paths' branch indices past 2^32 (the
// Sobol sequence's own length) are samples of their own, not repeats of the
// first samples' branches, and --samples refuses what the renderer cannot
// index. The whisker binary end to end, and the renderer in process.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "render_util.h"
#include "run_whisker.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace whisker;

namespace {

// The pixels' luminances of a PFM file (whisker's: "PF", size, scale, floats).
std::vector<double> pfm_luminance(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::string magic;
  int w = 0, h = 0;
  double scale = 0.0;
  in >> magic >> w >> h >> scale;
  in.get();
  std::vector<float> rgb(std::size_t(w) * std::size_t(h) * 3);
  in.read(reinterpret_cast<char*>(rgb.data()), std::streamsize(rgb.size() * sizeof(float)));
  EXPECT_TRUE(magic == "PF" && in) << p;
  std::vector<double> out;
  for (std::size_t i = 0; i < rgb.size(); i += 3)
    out.push_back(kLuminanceWeights[0] * rgb[i] + kLuminanceWeights[1] * rgb[i + 1] +
                  kLuminanceWeights[2] * rgb[i + 2]);
  return out;
}

class SampleIndex : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ifstream in(fs::path(WHISKER_ASSETS_DIR) / "scenes" / "indirect.json");
    nlohmann::json j = nlohmann::json::parse(in);
    j["camera"]["width"] = 8;
    j["camera"]["height"] = 6;
    scene = dir / "room.json";
    std::ofstream(scene) << j.dump(2);
  }
  // The red team's settings: every sample's light goes through its branches
  // (no jitter, no Fresnel choice, no light connections), 64 x 64 of them
  // whatever the colour (split weights 1), depth 2 so both levels split.
  Result render(const std::string& samples, const std::string& out) {
    return run("--headless --quiet --threads 2 --scene " + scene.string() +
               " --split 64,64 --split-weights 1,1,1 --aa off --fresnel off --connect off "
               "--depth 2 --spp 4 --samples " + samples + " --out-float " + f(out));
  }
  std::string f(const std::string& name) const { return (dir / name).string(); }

  TempDir temp{"sample-index"};
  const fs::path dir = temp.path();
  fs::path scene;
};

}  // namespace

// Sample 2^26's branches have indices 2^32 + k and 2^38 + k: in 32 bits they
// were sample 0's, and --samples 2^26:2^26+4 rendered byte for byte the image
// of 0:4. Now the two are different estimates of the same image: the mean of
// their pixel differences is within 4 standard errors of 0.
TEST_F(SampleIndex, BranchesPast2To32AreNotTheFirstSamplesAgain) {
  for (const auto& [samples, out] : {std::pair{"0:4", "low.pfm"}, {"67108864:67108868", "high.pfm"}}) {
    const Result r = render(samples, out);
    ASSERT_EQ(r.code, 0) << samples << "\n" << r.output;
  }
  const std::vector<double> a = pfm_luminance(f("low.pfm")), b = pfm_luminance(f("high.pfm"));
  ASSERT_EQ(a.size(), 48u);
  ASSERT_EQ(b.size(), a.size());
  double sum = 0.0, sum2 = 0.0;
  int differ = 0;
  for (std::size_t p = 0; p < a.size(); ++p) {
    const double d = a[p] - b[p];
    differ += d != 0.0;
    sum += d;
    sum2 += d * d;
  }
  // (A few pixels see only direct light: the same in every render.)
  EXPECT_GT(differ, int(a.size()) / 2) << "pixels of 2^26:2^26+4 that differ from 0:4";
  const double n = double(a.size()), mean = sum / n;
  const double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1.0));
  EXPECT_LT(std::abs(mean), 4.0 * se) << "mean difference " << mean << ", standard error " << se;
}

// With --split 16, sample 2^28's branches start at 2^32. In process, 64
// samples per pixel from sample 2^28 against 64 from sample 0: different
// sums, the same expectation pixel by pixel (z-scores, render_util.h).
TEST_F(SampleIndex, BranchesPast2To32EstimateTheSameImage) {
  Scene s = sized("indirect", 8, 6, 16, 64);
  s.settings.split = {16};
  s.settings.split_weights = vec3(1.0f);
  s.settings.aa = s.settings.fresnel = s.settings.connect = false;
  s.settings.max_depth = 2;
  Snapshot snap[2];
  for (int h = 0; h < 2; ++h) {
    ProgressiveRenderer r(2);
    const auto gen = r.set_scene(s, RenderStart{h ? 1ull << 28 : 0, nullptr});
    r.start();
    ASSERT_TRUE(r.wait_for(gen, 64));
    r.snapshot(snap[h]);
    r.stop();
    ASSERT_EQ(snap[h].spp, 64u);
    ASSERT_EQ(snap[h].first_sample, h ? 1ull << 28 : 0);
  }
  // (A few pixels see only direct light: the same in every render.)
  const std::size_t pixels = snap[0].sum_sq.size();
  int differ = 0;
  for (std::size_t p = 0; p < pixels; ++p)
    differ += pixel_stat(snap[0], p).mean != pixel_stat(snap[1], p).mean;
  EXPECT_GT(differ, int(pixels) / 2) << "pixels of 2^28:2^28+64 that differ from 0:64";
  expect_same_expectation(snap[0], snap[1], "samples 0:64 against 2^28:2^28+64");
}

// The index space holds every range --samples accepts (below 2^30, through
// at most 4096 branches: below 2^42); a range past it is refused up front,
// in one line naming the option.
TEST_F(SampleIndex, RangePastTheLimitIsRefusedInOneLine) {
  const Result r = render("1073741823:1073741825", "never.pfm");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.output,
            "whisker: --samples 1073741823:1073741825: sample indices must stay below 2^30\n");
  EXPECT_FALSE(fs::exists(f("never.pfm")));
}
