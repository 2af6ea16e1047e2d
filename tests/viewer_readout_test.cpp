// The viewer's window-free numbers: progress and time left, a pixel's
// statistics, the display mapping used for saving, free file names.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "io/image_io.h"
#include "render/progressive.h"
#include "scene/scene_io.h"
#include "viewer/readout.h"
#include "viewer/viewer_state.h"
#include "temp_dir.h"

using namespace whisker;

TEST(Progress, CountsThePassInFlightAndEstimatesFromTheRate) {
  ProgressInput in;
  in.spp_done = 10;
  in.target_spp = 100;
  in.seconds_done = 5.0;
  in.pass_spp = 10;
  in.tiles_done = 50;
  in.tiles_total = 100;
  in.pass_seconds = 2.5;
  const ProgressInfo p = estimate_progress(in);
  EXPECT_DOUBLE_EQ(p.pass_fraction, 0.5);
  EXPECT_DOUBLE_EQ(p.done_spp, 15.0);
  EXPECT_DOUBLE_EQ(p.elapsed, 7.5);
  EXPECT_DOUBLE_EQ(p.spp_per_second, 2.0);
  EXPECT_DOUBLE_EQ(p.fraction, 0.15);
  EXPECT_DOUBLE_EQ(p.eta, 42.5);  // 85 spp left at 2 spp/s
}

// Rates and time left come from published passes only: a pass in flight
// moves the bar but not the rate (a preview's or a partial pass's rate is
// not the render's).
TEST(Progress, RatesComeFromPublishedPassesOnly) {
  ProgressInput in;
  in.target_spp = 64;
  in.pass_spp = 64;  // one pass for the whole target
  in.tiles_done = 16;
  in.tiles_total = 256;
  in.pass_seconds = 4.0;
  ProgressInfo p = estimate_progress(in);
  EXPECT_DOUBLE_EQ(p.done_spp, 4.0);
  EXPECT_EQ(p.spp_per_second, 0.0);  // "-": no pass is in yet
  EXPECT_LT(p.eta, 0.0);
  in.spp_done = 8;
  in.seconds_done = 2.0;
  in.pass_spp = 8;
  in.tiles_done = 128;  // half of the next pass: not in the rate
  in.pass_seconds = 10.0;
  p = estimate_progress(in);
  EXPECT_DOUBLE_EQ(p.spp_per_second, 4.0);
  EXPECT_DOUBLE_EQ(p.eta, (64.0 - 12.0) / 4.0);
}

TEST(Progress, NoTargetNoEtaAndNothingDoneNoRate) {
  ProgressInput in;
  in.spp_done = 8;
  in.seconds_done = 2.0;
  ProgressInfo p = estimate_progress(in);
  EXPECT_LT(p.fraction, 0.0);
  EXPECT_LT(p.eta, 0.0);
  EXPECT_DOUBLE_EQ(p.spp_per_second, 4.0);
  p = estimate_progress(ProgressInput{});
  EXPECT_EQ(p.spp_per_second, 0.0);
  in.target_spp = 8;  // reached
  EXPECT_EQ(estimate_progress(in).eta, 0.0);
  EXPECT_EQ(estimate_progress(in).fraction, 1.0);
}

TEST(Progress, DurationsReadAsTime) {
  EXPECT_EQ(format_duration(12.34), "12.3 s");
  EXPECT_EQ(format_duration(185.0), "3m 05s");
  EXPECT_EQ(format_duration(3720.0), "1h 02m");
  EXPECT_EQ(format_duration(-1.0), "-");
}

TEST(PixelReadout, MeanAndStandardErrorOfThePixel) {
  Snapshot s;
  s.width = 2;
  s.height = 1;
  s.spp = 2;
  // Pixel 1 saw grey samples 1 and 3: mean 2, sample variance 2, so the
  // mean's standard error is sqrt(2 / 2) = 1.
  s.sum = {0, 0, 0, 4, 4, 4};
  s.sum_sq = {0, 1 + 9};
  const PixelReadout r = read_pixel(s, 1, 0);
  EXPECT_FLOAT_EQ(r.rgb[0], 2.0f);
  EXPECT_NEAR(r.luminance, 2.0, 1e-6);
  EXPECT_NEAR(r.std_error, 1.0, 1e-6);
  EXPECT_EQ(r.samples, 2u);
  s.spp = 1;
  EXPECT_LT(read_pixel(s, 1, 0).std_error, 0.0);  // needs 2 samples
  EXPECT_EQ(read_pixel(s, 2, 0).samples, 0u);     // outside
}

// The readout's last line counts the samples behind the pixel: "1 sample"
// at one sample per pixel, "N samples" otherwise; the first names the pixel
// and, on the held side of a comparison, the held image.
TEST(PixelReadout, LinesSaySampleOrSamples) {
  Snapshot s;
  s.width = 2;
  s.height = 1;
  s.spp = 1;
  s.sum = {0, 0, 0, 4, 4, 4};
  s.sum_sq = {0, 16};
  std::vector<std::string> lines = readout_lines(read_pixel(s, 1, 0), 1, 0, false);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "pixel (1, 0)");
  EXPECT_EQ(lines[1], "radiance  4  4  4");
  EXPECT_EQ(lines[2], "luminance 4  (error needs 2 samples)");
  EXPECT_EQ(lines[3], "1 sample (std. error of the pixel mean)");
  for (const std::uint64_t n : {2ull, 16ull, 1024ull}) {
    s.spp = n;
    lines = readout_lines(read_pixel(s, 1, 0), 1, 0, true);
    EXPECT_EQ(lines[0], "pixel (1, 0)  [held image]");
    EXPECT_EQ(lines[3], std::to_string(n) + " samples (std. error of the pixel mean)");
  }
  s.spp = 0;  // nothing rendered yet
  EXPECT_EQ(readout_lines(read_pixel(s, 1, 0), 1, 0, false)[3],
            "0 samples (std. error of the pixel mean)");
}

// The readout's box goes beside the pointer away from the image's centre,
// and to the other side where it would leave the image: never over the
// panel right of the image, never below the window, never over the centre
// where it fits on the outer side.
TEST(PixelReadout, BoxStaysOverTheImage) {
  const float ax = 0, ay = 144, aw = 512, ah = 512, w = 330, h = 84;
  const auto inside = [&](const BoxPlace& p) {
    return p.x >= ax && p.y >= ay && p.x + w <= ax + aw && p.y + h <= ay + ah;
  };
  // Top left quarter: above the pointer; left of it there is no room.
  const BoxPlace upper_left = place_readout(100, 300, w, h, ax, ay, aw, ah);
  EXPECT_FLOAT_EQ(upper_left.x, 116);
  EXPECT_FLOAT_EQ(upper_left.y, 208);
  // A narrower box near the centre: below right of the pointer in the
  // bottom right quarter, above left of it in the top left one.
  const float narrow = 150;
  const BoxPlace lower_right = place_readout(270, 410, narrow, h, ax, ay, aw, ah);
  EXPECT_FLOAT_EQ(lower_right.x, 286);
  EXPECT_FLOAT_EQ(lower_right.y, 418);
  const BoxPlace upper_left_narrow = place_readout(200, 390, narrow, h, ax, ay, aw, ah);
  EXPECT_FLOAT_EQ(upper_left_narrow.x, 200 - 8 - narrow);
  EXPECT_FLOAT_EQ(upper_left_narrow.y, 390 - 8 - h);
  // Top right with the wide box: above; neither side has room, so it
  // keeps to the image's left edge.
  const BoxPlace upper_right = place_readout(300, 390, w, h, ax, ay, aw, ah);
  EXPECT_FLOAT_EQ(upper_right.x, 0);
  EXPECT_FLOAT_EQ(upper_right.y, 390 - 8 - h);
  const float cx = ax + aw / 2, cy = ay + ah / 2;
  for (const float mx : {180.0f, 240.0f, 250.0f, 262.0f, 300.0f, 340.0f})
    for (const float my : {250.0f, 330.0f, 395.0f, 405.0f, 470.0f, 560.0f}) {
      const BoxPlace p = place_readout(mx, my, w, h, ax, ay, aw, ah);
      EXPECT_FALSE(cx >= p.x && cx < p.x + w && cy >= p.y && cy < p.y + h)
          << "pointer " << mx << ", " << my << ": the box at " << p.x << ", " << p.y << " covers the centre";
    }
  for (const float mx : {0.0f, 100.0f, 255.0f, 400.0f, 511.0f})
    for (const float my : {144.0f, 300.0f, 600.0f, 655.0f}) {
      const BoxPlace p = place_readout(mx, my, w, h, ax, ay, aw, ah);
      EXPECT_TRUE(inside(p)) << "pointer " << mx << ", " << my << ": box at " << p.x << ", " << p.y;
      // Never under the pointer: the box is beside it.
      EXPECT_FALSE(mx >= p.x && mx < p.x + w && my >= p.y && my < p.y + h) << mx << ", " << my;
    }
}

TEST(ToneCurve, AcesFitValues) {
  EXPECT_EQ(aces_narkowicz(0.0f), 0.0f);
  // x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) at x = 1: 2.54 / 3.16.
  EXPECT_NEAR(aces_narkowicz(1.0f), 2.54f / 3.16f, 1e-6f);
  EXPECT_EQ(aces_narkowicz(1e6f), 1.0f);  // highlights roll off to white
  EXPECT_LT(aces_narkowicz(0.5f), aces_narkowicz(0.6f));
}

// At the report's mapping the saved PNG is the headless PNG to the bit; an
// exposure of +1 stop is the report's mapping of twice the radiance.
TEST(SaveMapping, ReportMappingMatchesTheHeadlessPng) {
  Scene scene = load_scene(resolve_scene("three-balls"));
  scene.camera.width = 48;
  scene.camera.height = 40;
  scene.settings.spp = 2;
  scene.settings.target_spp = 2;
  ProgressiveRenderer r(1);
  const auto gen = r.set_scene(scene);
  r.start();
  ASSERT_TRUE(r.wait_for(gen, 2));
  Snapshot s;
  r.snapshot(s);
  r.stop();
  const Image img = mean_image(s);
  DisplayParams p;
  p.exposure = report_exposure();
  const auto out = map_like_display(s, p);
  ASSERT_EQ(out.size(), img.rgb.size());
  for (std::size_t k = 0; k < out.size(); ++k) ASSERT_EQ(out[k], to_srgb8(img.rgb[k])) << k;

  p.exposure = 2.0f * report_exposure();
  const auto brighter = map_like_display(s, p);
  int off = 0;
  for (std::size_t k = 0; k < out.size(); ++k)
    off += std::abs(int(brighter[k]) - int(to_srgb8(2.0f * img.rgb[k]))) > 1;
  EXPECT_EQ(off, 0);
  p.tonemap = kTonemapAces;
  const auto aces = map_like_display(s, p);
  for (std::size_t k = 0; k < out.size(); ++k) {
    const float v = std::pow(aces_narkowicz(img.rgb[k] * p.exposure), 1.0f / 2.2f);
    ASSERT_NEAR(aces[k], std::floor(v * 255.0f), 1.0) << k;
  }
}

TEST(SaveName, NeverOverwrites) {
  namespace fs = std::filesystem;
  const TempDir temp("free-stem");
  const fs::path& dir = temp.path();
  const std::vector<std::string> exts = {".png", ".exr"};
  EXPECT_EQ(free_stem(dir.string(), "cat-16spp", exts), "cat-16spp");
  std::ofstream(dir / "cat-16spp.png") << "x";
  EXPECT_EQ(free_stem(dir.string(), "cat-16spp", exts), "cat-16spp-2");
  std::ofstream(dir / "cat-16spp-2.exr") << "x";  // either file takes the name
  EXPECT_EQ(free_stem(dir.string(), "cat-16spp", exts), "cat-16spp-3");
}

// Sampling > stop at: the noise limit once the error is known and low
// enough, the time limit once the render time reaches it, off at 0.
TEST(StopAt, NoiseOrTimeReached) {
  const double nan = std::nan("");
  EXPECT_EQ(stop_reason(0.05, 10.0, 0.0f, 0.0f), "");     // both off
  EXPECT_EQ(stop_reason(nan, 10.0, 5.0f, 0.0f), "");      // no error yet
  EXPECT_EQ(stop_reason(0.051, 10.0, 5.0f, 0.0f), "");    // 5.1 % > 5 %
  EXPECT_EQ(stop_reason(0.05, 10.0, 5.0f, 0.0f), "noise 5 % reached");
  EXPECT_EQ(stop_reason(0.02, 10.0, 2.5f, 0.0f), "noise 2.5 % reached");
  EXPECT_EQ(stop_reason(0.5, 9.9, 0.0f, 10.0f), "");
  EXPECT_EQ(stop_reason(0.5, 10.0, 0.0f, 10.0f), "10.0 s reached");
  EXPECT_EQ(stop_reason(0.5, 75.0, 1.0f, 60.0f), "1m 00s reached");
}
