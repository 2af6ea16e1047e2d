// End to end: the whisker binary in headless mode, on every sphere scene,
// and its answers to bad input.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "io/image_io.h"
#include "scene/settings.h"
#include "run_whisker.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace whisker;

namespace {

// Reads back the 8-bit PNG through the PNG's own header: width and height.
std::pair<int, int> png_size(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), 24);
  if (std::string(reinterpret_cast<char*>(h) + 1, 3) != "PNG") return {0, 0};
  auto be = [&](int o) { return (h[o] << 24) | (h[o + 1] << 16) | (h[o + 2] << 8) | h[o + 3]; };
  return {be(16), be(20)};
}

}  // namespace

TEST(Headless, EverySphereSceneWritesPngFloatImageAndStats) {
  const TempDir temp("e2e");
  const fs::path& dir = temp.path();
  for (const char* name : {"diffuse-ball", "three-balls", "three-balls-fresnel", "indirect",
                           "antialiased-ball"}) {
    const fs::path png = dir / (std::string(name) + ".png");
    const fs::path pfm = dir / (std::string(name) + ".pfm");
    const fs::path stats = dir / (std::string(name) + ".json");
    const Result r = run(std::string("--headless --quiet --scene ") + name +
                         " --frames 2 --out " + png.string() + " --out-float " + pfm.string() +
                         " --stats " + stats.string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("2 spp"), std::string::npos) << r.output;
    EXPECT_EQ(png_size(png), std::make_pair(512, 512));
    const Image img = read_pfm(pfm.string());
    EXPECT_EQ(img.width, 512);
    std::ifstream sj(stats);
    const auto j = nlohmann::json::parse(sj);
    EXPECT_EQ(j["spp"], 2);
    EXPECT_EQ(j["nan_count"], 0);
    EXPECT_GT(j["rays_per_s"].get<double>(), 0.0);
    // The centre pixel sees a ball or what is behind it, never black.
    const float c = img.rgb[(256 * 512 + 256) * 3 + 0] + img.rgb[(256 * 512 + 256) * 3 + 1] +
                    img.rgb[(256 * 512 + 256) * 3 + 2];
    EXPECT_GT(c, 0.0f) << name;
  }
  // No temporary files are left behind.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST(Headless, SplitWeightsReachTheRendererAndTheStats) {
  // The indirect scene (split 4,4 by default): weights of 0.25 make every
  // split round(4 * 0.25) = 1, so a sample traces fewer rays; the stats
  // record the weights used.
  const TempDir temp("e2e");
  const fs::path& dir = temp.path();
  auto rays = [&](const std::string& extra, nlohmann::json& j) {
    const fs::path stats = dir / "s.json";
    const Result r = run("--headless --quiet --scene indirect --frames 1 --spp 1 --seed 3 --out-float " +
                         (dir / "x.pfm").string() + " --stats " + stats.string() + extra);
    EXPECT_EQ(r.code, 0) << r.output;
    std::ifstream sj(stats);
    j = nlohmann::json::parse(sj);
    return j["rays"].get<double>();
  };
  nlohmann::json plain, weighted;
  const double full = rays("", plain);
  const double fewer = rays(" --split-weights 0.25,0.25,0.25", weighted);
  EXPECT_EQ(plain["settings"]["split_weights"], nlohmann::json({1.0, 1.0, 1.0}));
  EXPECT_EQ(weighted["settings"]["split_weights"], nlohmann::json({0.25, 0.25, 0.25}));
  EXPECT_LT(fewer, 0.5 * full);
  // The settings block holds every setting of the table, by its scene-file key.
  for (const SettingField& f : setting_fields())
    EXPECT_TRUE(plain["settings"].contains(f.key)) << f.key;
  EXPECT_EQ(plain["settings"]["split"], nlohmann::json({4, 4}));
  EXPECT_EQ(plain["settings"]["sampler"], "sobol");
}

TEST(Headless, PngFollowsTheReportsMapping) {
  const TempDir temp("e2e");
  const fs::path& dir = temp.path();
  const Result r = run("--headless --quiet --scene diffuse-ball --out " + (dir / "a.png").string() +
                       " --out-float " + (dir / "a.pfm").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(to_srgb8(0.0f), 0);
  EXPECT_EQ(to_srgb8(std::pow(100.0f, 2.2f)), 99);  // float rounding just below 100
  EXPECT_EQ(to_srgb8(std::pow(255.0f, 2.2f) * 2), 255);
  EXPECT_EQ(to_srgb8(std::pow(100.5f, 2.2f)), 100);
}

TEST(Headless, OpenExrWhenBuiltWithIt) {
  if (!have_exr()) GTEST_SKIP() << "built without OpenEXR";
  const TempDir temp("e2e");
  const fs::path& dir = temp.path();
  const fs::path exr = dir / "a.exr";
  const Result r = run("--headless --quiet --scene diffuse-ball --out-float " + exr.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(exr, std::ios::binary);
  unsigned char magic[4] = {};
  in.read(reinterpret_cast<char*>(magic), 4);
  EXPECT_EQ(magic[0], 0x76);  // OpenEXR magic number 20000630
  EXPECT_EQ(magic[1], 0x2f);
  EXPECT_EQ(magic[2], 0x31);
  EXPECT_EQ(magic[3], 0x01);
  // The header names float R, G, B channels over 512 x 512 pixels.
  std::string header(4096, '\0');
  in.read(header.data(), std::streamsize(header.size()));
  EXPECT_NE(header.find("channels"), std::string::npos);
  EXPECT_NE(header.find("dataWindow"), std::string::npos);
  EXPECT_GT(fs::file_size(exr), 100000u);  // compressed float data, not an empty shell
}

TEST(Headless, BadInputExitsTwoWithAMessage) {
  const TempDir temp("e2e");
  const fs::path& dir = temp.path();
  const std::string out = " --out " + (dir / "x.png").string();
  struct Case { std::string args; std::string expect; };
  std::ofstream(dir / "broken.json") << "{\"spheres\": [ {\"radius\": 3 }";
  std::ofstream(dir / "typo.json") << "{\"light\": {\"positon\": [0, 0, 0]}}";
  const Case cases[] = {
      {"--headless --frames -1 --scene three-balls" + out, "--frames"},
      {"--headless --frames 0 --scene three-balls" + out, "--frames"},
      {"--headless --bogus" + out, "--bogus"},
      {"--headless --scene no-such-scene" + out, "no-such-scene.json: scene file not found"},
      {"--headless --scene " + (dir / "broken.json").string() + out, "broken.json:1:"},
      {"--headless --scene " + (dir / "typo.json").string() + out, "light.positon: unknown key"},
      {"--headless --scene three-balls --out /no/such/dir/x.png", "/no/such/dir does not exist"},
      {"--headless --scene three-balls --out " + (dir / "x.jpg").string(), "must end in .png"},
      {"--headless --scene three-balls --out-float " + (dir / "x.tiff").string(), "must end in .pfm or .exr"},
      {"--headless --scene three-balls --light 1,2" + out, "--light 1,2: expected three finite numbers"},
      {"--headless --scene three-balls --indirect maybe" + out, "--indirect"},
      {"--headless --scene three-balls --spp 0" + out, "--spp"},
      {"--headless --scene three-balls --split 4,x" + out, "--split 4,x: expected integers separated by commas"},
      {"--headless --scene three-balls --split 4,0" + out, "--split 4,0: factors must be in [1, 64], got 0"},
      {"--headless --scene three-balls --split 64,64,64" + out, "--split 64,64,64: the factors' product"},
      {"--headless --scene three-balls --split-weights 1,0,1" + out, "--split-weights 1,0,1: expected three numbers r,g,b in [0.01, 1]"},
      {"--headless --scene three-balls --split-weights 1,1" + out, "--split-weights 1,1: expected three numbers"},
      {"--headless --scene three-balls --spp 65536 --frames 65536" + out, "more than 2^30 samples per pixel"},
      {"--headless --scene three-balls", "needs at least one of --out"},
  };
  for (const Case& c : cases) {
    const Result r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.find("terminate"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

TEST(Headless, CommandLineOverridesTheScene) {
  // Moving the light with --light changes the image; the same command twice
  // gives the same bytes (determinism end to end).
  const TempDir temp("e2e");
  const fs::path& dir = temp.path();
  auto render = [&](const std::string& extra, const std::string& file) {
    const Result r = run("--headless --quiet --scene diffuse-ball --out-float " + (dir / file).string() + extra);
    EXPECT_EQ(r.code, 0) << r.output;
    return read_pfm((dir / file).string()).rgb;
  };
  const auto a = render("", "a.pfm");
  const auto b = render(" --light 10,20,40", "b.pfm");
  const auto c = render(" --threads 1", "c.pfm");
  EXPECT_NE(a, b);
  EXPECT_EQ(a, c);
}

TEST(Headless, AnExactEstimateRendersOnePassWhateverItsTargetSpp) {
  // No indirect light, no anti-aliasing, no Fresnel choice: every pass is the
  // same image, so --target-spp 64 renders one pass (as the viewer stops
  // after one), says so on stderr once, and records what the pass stands
  // for; its image is that of --frames 1, bit for bit.
  const TempDir temp("e2e");
  const fs::path& dir = temp.path();
  const std::string base =
      "--headless --quiet --scene diffuse-ball --indirect off --aa off --fresnel off --spp 1 ";
  const fs::path one = dir / "one.pfm", asked = dir / "asked.pfm", stats = dir / "asked.json";
  const Result r1 = run(base + "--frames 1 --out-float " + one.string());
  ASSERT_EQ(r1.code, 0) << r1.output;
  const Result r = run(base + "--target-spp 64 --out-float " + asked.string() + " --stats " +
                       stats.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream sj(stats);
  const auto j = nlohmann::json::parse(sj);
  EXPECT_EQ(j["passes"], 1);
  EXPECT_EQ(j["spp"], 1);
  EXPECT_EQ(j["exact"], true);
  EXPECT_EQ(j["stands_for_spp"], 64);
  EXPECT_EQ(j["settings"]["target_spp"], 64);
  const std::string said =
      "whisker: --target-spp 64: the estimate is deterministic (no indirect light, no "
      "anti-aliasing, no Fresnel choice), so one pass of 1 spp is exact and stands for it; "
      "rendering that one pass\n";
  const std::size_t at = r.output.find(said);
  EXPECT_NE(at, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(said, at + 1), std::string::npos) << "said twice: " << r.output;
  EXPECT_EQ(file_bytes(one), file_bytes(asked));
  // An EXR records it: "whisker.exact" and the samples it stands for.
  if (have_exr()) {
    const fs::path exr = dir / "asked.exr";
    ASSERT_EQ(run(base + "--target-spp 64 --out-float " + exr.string()).code, 0);
    const std::string header = file_bytes(exr);
    const std::string attr = std::string("whisker.stands_for_spp\0string\0\x02\0\0\0" "64", 36);
    EXPECT_NE(header.find(attr), std::string::npos);
    EXPECT_NE(header.find(std::string("whisker.exact\0string\0\x04\0\0\0" "true", 29)),
              std::string::npos);
  }
  // --frames N is a count of passes: it renders them all.
  const Result frames = run(base + "--frames 3 --out-float " + asked.string() + " --stats " +
                            stats.string());
  ASSERT_EQ(frames.code, 0) << frames.output;
  std::ifstream sj3(stats);
  EXPECT_EQ(nlohmann::json::parse(sj3)["passes"], 3);
}
