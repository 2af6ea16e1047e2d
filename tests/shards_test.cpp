// Sample-range shards, accumulation files, merge and resume: the whisker
// binary end to end (the accumulation file format on its own:
// accumulation_io_test.cpp, its checksums: part_checks_test.cpp). The
// exactness claims are checked bit for bit: output files byte for byte, sums
// by their bit patterns.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "io/accumulation_io.h"
#include "run_whisker.h"
#include "same_bits.h"
#include "sanitized.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace whisker;

namespace {

// The indirect room at 96x96 with Fresnel glass and anti-aliasing on, so the
// shards go through pixel jitter, splitting (4,4 branches per sample, whose
// Sobol indices are i*K+k of the global sample index i), the Fresnel choice
// and light connections (each pass's shared light paths, read sample-major).
class Shards : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ifstream in(fs::path(WHISKER_ASSETS_DIR) / "scenes" / "indirect.json");
    nlohmann::json j = nlohmann::json::parse(in);
    j["camera"]["width"] = 96;
    j["camera"]["height"] = 96;
    j["settings"]["fresnel"] = true;
    j["settings"]["aa"] = true;
    j["settings"]["connect"] = true;
    scene = dir / "room.json";
    std::ofstream(scene) << j.dump(2);
  }
  // whisker --headless on the small room with `args`; expects success.
  void render(const std::string& args) {
    const Result r = run("--headless --quiet --threads 2 --scene " + scene.string() + " " + args);
    ASSERT_EQ(r.code, 0) << args << "\n" << r.output;
  }
  std::string f(const std::string& name) const { return (dir / name).string(); }

  TempDir temp{"shards"};
  const fs::path dir = temp.path();
  fs::path scene;
};

}  // namespace

TEST_F(Shards, MergedRangesEqualTheRenderWithThoseRangesAsPassesBitForBit) {
  for (const char* sampler : {"sobol", "independent"}) {
    SCOPED_TRACE(sampler);
    const std::string s = std::string(" --sampler ") + sampler + " --spp 3";
    // The reference: an ordinary render of 2 passes of 3 samples.
    render(s + " --frames 2 --out-float " + f("frames.pfm"));
    render(s + " --samples 0:6 --out-float " + f("full.pfm") + " --out-sum " + f("full.exr"));
    render(s + " --samples 0:3 --out-sum " + f("a.exr") + " --out-float " + f("a.pfm"));
    render(s + " --samples 3:6 --out-sum " + f("b.exr") + " --out-float " + f("b.pfm"));
    // The second part holds other samples than the first (its own indices).
    EXPECT_NE(file_bytes(f("a.pfm")), file_bytes(f("b.pfm")));
    // Given out of order: the merge folds in range order. (--out takes one
    // value each time, so the parts may follow it.)
    const Result m = run("merge --out " + f("m.pfm") + " " + f("b.exr") + " " + f("a.exr") +
                         " --out " + f("m.exr") + " --out " + f("m.png"));
    ASSERT_EQ(m.code, 0) << m.output;
    EXPECT_NE(m.output.find("samples 0:6"), std::string::npos) << m.output;
    EXPECT_EQ(file_bytes(f("frames.pfm")), file_bytes(f("full.pfm")));
    EXPECT_EQ(file_bytes(f("full.pfm")), file_bytes(f("m.pfm")));
    const Accumulation full = read_accumulation(f("full.exr"));
    const Accumulation merged = read_accumulation(f("m.exr"));
    EXPECT_TRUE(same_bits(full.sum, merged.sum));
    EXPECT_TRUE(same_bits(full.sum_sq, merged.sum_sq));
    EXPECT_EQ(merged.ranges, (std::vector<SampleRange>{{0, 6}}));
    EXPECT_EQ(merged.counters.passes, 2u);
    EXPECT_TRUE(fs::file_size(f("m.png")) > 0);
  }
}

TEST_F(Shards, ResumeContinuesExactlyAndACompletePartIsNotRenderedAgain) {
  render("--spp 2 --frames 3 --out-float " + f("full.pfm"));
  render("--spp 2 --frames 1 --out-sum " + f("part.exr"));
  render("--spp 2 --frames 3 --resume " + f("part.exr") + " --out-float " + f("resumed.pfm") +
         " --out-sum " + f("resumed.exr"));
  EXPECT_EQ(file_bytes(f("full.pfm")), file_bytes(f("resumed.pfm")));
  EXPECT_EQ(read_accumulation(f("resumed.exr")).ranges, (std::vector<SampleRange>{{0, 6}}));
  // --samples may name the continuation instead of --frames.
  render("--spp 2 --samples 2:6 --resume " + f("part.exr") + " --out-float " + f("r2.pfm"));
  EXPECT_EQ(file_bytes(f("full.pfm")), file_bytes(f("r2.pfm")));
  // Resuming a part that already holds every sample writes it as it is.
  render("--spp 2 --frames 3 --resume " + f("resumed.exr") + " --out-float " + f("again.pfm"));
  EXPECT_EQ(file_bytes(f("full.pfm")), file_bytes(f("again.pfm")));
}

TEST_F(Shards, AKilledRenderResumesFromItsCheckpointExactly) {
  // Enough passes that the kill below lands before the last one (a pass
  // takes about 10 ms in Release, 10x that under a sanitizer).
  const std::string frames = std::to_string(release_or_sanitized(120, 30));
  render("--spp 1 --frames " + frames + " --out-float " + f("full.pfm"));
  // Killed (SIGKILL, no chance to clean up) once the first checkpoint is there.
  const std::string cmd = std::string(WHISKER_BIN) + " --headless --quiet --threads 2 --scene " +
                          scene.string() + " --spp 1 --frames " + frames +
                          " --checkpoint 0 --out-sum " + f("ck.exr") + " & pid=$!; while [ ! -f " +
                          f("ck.exr") + " ]; do sleep 0.02; done; kill -9 $pid; wait $pid";
  ASSERT_NE(std::system(cmd.c_str()), -1);
  const Accumulation part = read_accumulation(f("ck.exr"));
  ASSERT_EQ(part.ranges.size(), 1u);
  EXPECT_EQ(part.ranges[0].begin, 0u);
  EXPECT_LT(part.ranges[0].end, std::stoull(frames)) << "the render finished before it was killed";
  EXPECT_EQ(part.counters.passes, part.ranges[0].end);
  render("--spp 1 --frames " + frames + " --resume " + f("ck.exr") + " --out-float " +
         f("resumed.pfm"));
  EXPECT_EQ(file_bytes(f("full.pfm")), file_bytes(f("resumed.pfm")));
  const Result r = run("--headless --scene " + scene.string() + " --checkpoint 5 --out " + f("x.png"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("--checkpoint needs --out-sum"), std::string::npos) << r.output;
}

TEST_F(Shards, BadMergesAndResumesAreRefusedNamingFilesAndField) {
  render("--spp 2 --samples 0:2 --out-sum " + f("a.exr"));
  render("--spp 2 --samples 1:3 --out-sum " + f("over.exr"));
  render("--spp 2 --samples 4:6 --out-sum " + f("later.exr"));
  render("--spp 2 --samples 2:4 --seed 7 --out-sum " + f("seed7.exr"));
  render("--spp 2 --samples 2:4 --light 0,30,40 --out-sum " + f("light.exr"));
  {  // the same room under another name: another scene
    std::ifstream in(scene);
    nlohmann::json j = nlohmann::json::parse(in);
    j["name"] = "other-room";
    std::ofstream(dir / "other.json") << j.dump(2);
  }
  const Result other = run("--headless --quiet --threads 2 --scene " + f("other.json") +
                           " --spp 2 --samples 2:4 --out-sum " + f("other.exr"));
  ASSERT_EQ(other.code, 0) << other.output;
  {  // a part cut short (a copy that did not finish, a full disk)
    const std::string whole = file_bytes(f("a.exr"));
    std::ofstream(f("cut.exr"), std::ios::binary) << whole.substr(0, whole.size() / 2);
  }
  fs::copy_file(f("a.exr"), f("a-copy.exr"));
  {  // the same room a row taller (its size is also in the scene file's hash)
    std::ifstream in(scene);
    nlohmann::json j = nlohmann::json::parse(in);
    j["camera"]["height"] = 97;
    std::ofstream(dir / "taller.json") << j.dump(2);
  }
  const Result taller = run("--headless --quiet --threads 2 --scene " + f("taller.json") +
                            " --spp 2 --samples 2:4 --out-sum " + f("taller.exr"));
  ASSERT_EQ(taller.code, 0) << taller.output;
  struct Case {
    std::string args, expect1, expect2;
  };
  const Case cases[] = {
      {f("a.exr") + " " + f("seed7.exr"), "seed7.exr", "settings.seed: 0 vs 7"},
      {f("a.exr") + " " + f("light.exr"), "light.exr", "scene file or meshes"},
      {f("a.exr") + " " + f("other.exr"), "scene: \"indirect\" vs \"other-room\"", "other.exr"},
      {f("a.exr") + " " + f("cut.exr"), "cut.exr", "cannot read as OpenEXR"},
      {f("a.exr") + " " + f("taller.exr"), "part " + f("taller.exr") + " is 96x97, part " + f("a.exr") + " is 96x96",
       "(the parts of one render have its size)"},
      {f("a.exr") + " " + f("a.exr"), "0:2 of " + f("a.exr"), "overlap"},
      {f("a.exr") + " " + f("a-copy.exr"), "0:2 of " + f("a-copy.exr"), "overlap"},
      {f("a.exr") + " " + f("over.exr"), "0:2 of " + f("a.exr"), "1:3 of " + f("over.exr")},
      {f("a.exr") + " " + f("later.exr"), "samples 2:4 are missing", "--partial"},
      {f("a.exr") + " " + f("nothere.exr"), "nothere.exr", "no such file"},
      {f("a.exr") + " " + scene.string(), "room.json", "OpenEXR"},
  };
  for (const Case& c : cases) {
    const Result r = run("merge " + c.args + " --out " + f("m.pfm"));
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expect1), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.expect2), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(f("m.pfm")));
  }
  // With --partial the merge is written and lists its ranges.
  const Result p = run("merge " + f("a.exr") + " " + f("later.exr") + " --partial --out " + f("p.exr"));
  EXPECT_EQ(p.code, 0) << p.output;
  EXPECT_NE(p.output.find("warning"), std::string::npos) << p.output;
  EXPECT_EQ(read_accumulation(f("p.exr")).ranges, (std::vector<SampleRange>{{0, 2}, {4, 6}}));
  // A resume of other settings, of a gapped part, or past the part's end.
  const std::pair<std::string, std::string> resumes[] = {
      {"--spp 2 --frames 2 --seed 7 --resume " + f("a.exr"), "settings.seed"},
      {"--spp 2 --frames 2 --resume " + f("taller.exr"), "differs in size: 96x97 vs 96x96 (file vs command line)"},
      {"--spp 2 --frames 4 --resume " + f("p.exr"), "not one range"},
      {"--spp 2 --samples 3:5 --resume " + f("a.exr"), "must start at 0 (the same --samples"},
      {"--spp 2 --samples 1:5 --resume " + f("a.exr"), "or at 2 (its continuation)"},
      {"--spp 2 --samples 0:4 --frames 2", "drop --frames"},
      {"--spp 2 --samples 4:2", "expected A:B"},
      {"--spp 2 --samples 0:4 --out-sum " + f("x.pfm"), "must end in .exr"},
  };
  for (const auto& [args, expect] : resumes) {
    const Result r = run("--headless --quiet --scene " + scene.string() + " --out-float " +
                         f("r.pfm") + " " + args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << r.output;
  }
}

TEST_F(Shards, ASampleRangeResumesWithTheSameCommandPlusResume) {
  // A render of --samples 2:6 in passes of one sample, killed after its
  // first checkpoint (which holds 2:3), goes on with the same command plus
  // --resume, to the same bits as the render never killed.
  render("--spp 1 --samples 2:6 --out-sum " + f("full.exr") + " --out-float " + f("full.pfm"));
  render("--spp 1 --samples 2:3 --out-sum " + f("ck.exr"));
  render("--spp 1 --samples 2:6 --resume " + f("ck.exr") + " --out-sum " + f("ck.exr") +
         " --out-float " + f("resumed.pfm"));
  const Accumulation full = read_accumulation(f("full.exr")), resumed = read_accumulation(f("ck.exr"));
  EXPECT_EQ(resumed.ranges, (std::vector<SampleRange>{{2, 6}}));
  EXPECT_TRUE(same_bits(full.sum, resumed.sum));
  EXPECT_EQ(file_bytes(f("full.pfm")), file_bytes(f("resumed.pfm")));
}

// The denoiser's feature buffers travel with the parts: a render split in
// parts (kept with --features) and merged holds the feature sums of the
// render done whole, bit for bit, and its denoised copy is the whole
// render's, byte for byte.
TEST_F(Shards, ShardedFeaturesMergeAndDenoiseBitForBitAsTheWholeRender) {
  for (const char* sampler : {"independent", "sobol"}) {
    SCOPED_TRACE(sampler);
    const std::string s = std::string(" --sampler ") + sampler + " --spp 3";
    render(s + " --frames 2 --out-denoised " + f("frames-dn.pfm") + " --out-float " + f("frames.exr"));
    render(s + " --samples 0:6 --out-sum " + f("full.exr") + " --out-denoised " + f("full-dn.pfm") +
           " --denoiser fast --out-float " + f("full.pfm"));
    render(s + " --samples 0:6 --out-denoised " + f("full-dn.exr"));
    render(s + " --samples 3:6 --features --out-sum " + f("b.exr"));
    render(s + " --samples 0:3 --features --out-sum " + f("a.exr"));
    const Result m = run("merge " + f("b.exr") + " " + f("a.exr") + " --out " + f("m.exr") + " --out-denoised " +
                         f("m-dn.pfm") + " --stats " + f("m.json"));
    ASSERT_EQ(m.code, 0) << m.output;
    const Accumulation full = read_accumulation(f("full.exr")), merged = read_accumulation(f("m.exr"));
    ASSERT_TRUE(full.with_features);
    ASSERT_TRUE(merged.with_features);
    EXPECT_TRUE(same_bits(full.features, merged.features));
    EXPECT_TRUE(same_bits(full.odd_rgb, merged.odd_rgb));
    EXPECT_TRUE(same_bits(full.sum, merged.sum));
    EXPECT_EQ(file_bytes(f("frames-dn.pfm")), file_bytes(f("m-dn.pfm")));
    // --denoiser means the same in a merge; a merged file merges and denoises again.
    const Result fast = run("merge " + f("m.exr") + " --denoiser fast --out-denoised " + f("m-fast.pfm"));
    ASSERT_EQ(fast.code, 0) << fast.output;
    EXPECT_EQ(file_bytes(f("full-dn.pfm")), file_bytes(f("m-fast.pfm")));
    EXPECT_NE(file_bytes(f("full-dn.pfm")), file_bytes(f("m-dn.pfm")));
    const nlohmann::json stats = nlohmann::json::parse(std::ifstream(f("m.json")));
    EXPECT_EQ(stats.at("denoised").at("filter"), "quality");
    EXPECT_EQ(stats.at("denoised").at("estimate_valid"), std::string(sampler) == "independent");
    // A float EXR holds the halves and their features as layers, and says so;
    // without feature buffers it holds neither.
    const std::string with = file_bytes(f("frames.exr"));
    for (const char* layer : {"even.albedo.R", "odd.normal.Z", "odd.depth.Z", "even.G", "whisker.features"})
      EXPECT_NE(with.find(layer), std::string::npos) << layer;
    EXPECT_NE(file_bytes(f("full-dn.exr")).find("whisker.image"), std::string::npos);
    render(s + " --frames 2 --out-float " + f("plain.exr"));
    const std::string plain = file_bytes(f("plain.exr"));
    EXPECT_EQ(plain.find("even.albedo.R"), std::string::npos);
    EXPECT_EQ(plain.find("whisker.features"), std::string::npos);
  }
}

// A part without feature buffers (rendered without them, or by a build
// before them) merges with parts that have them: the merge keeps none and
// says so in one line; asked to denoise, it refuses, naming the part.
TEST_F(Shards, PartsWithAndWithoutFeaturesMergeWithoutThemOrRefuseToDenoise) {
  render("--spp 2 --samples 0:2 --features --out-sum " + f("a.exr"));
  render("--spp 2 --samples 2:4 --out-sum " + f("b.exr"));
  render("--spp 2 --samples 2:4 --features --out-sum " + f("b-features.exr"));
  Result r = run("merge " + f("a.exr") + " " + f("b.exr") + " --out " + f("m.exr"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("whisker: warning: merge: " + f("b.exr") + " keeps no feature buffers (" + f("a.exr") +
                          " does); the merge keeps none\n"),
            std::string::npos) << r.output;
  EXPECT_FALSE(read_accumulation(f("m.exr")).with_features);
  // Both kinds merge to the same radiance.
  r = run("merge " + f("a.exr") + " " + f("b-features.exr") + " --out " + f("mf.exr"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
  EXPECT_TRUE(same_bits(read_accumulation(f("m.exr")).sum, read_accumulation(f("mf.exr")).sum));
  const std::pair<std::string, std::string> refusals[] = {
      {f("a.exr") + " " + f("b.exr"), "merge --out-denoised " + f("d.png") + ": " + f("b.exr") +
                                          " keeps no feature buffers (" + f("a.exr") + " does)\n"},
      {f("b.exr"), "the parts keep no feature buffers (render them with --features or --out-denoised)\n"},
      {f("a.exr") + " " + f("later.exr") + " --partial", "not one range"},
      {f("a.exr") + " --denoiser best", "--denoiser best: expected quality or fast"},
  };
  render("--spp 2 --samples 4:6 --features --out-sum " + f("later.exr"));
  for (const auto& [args, expect] : refusals) {
    r = run("merge " + args + " --out-denoised " + f("d.png") + " --out " + f("d.pfm"));
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(f("d.png")));
    EXPECT_FALSE(fs::exists(f("d.pfm")));
  }
}

// A resumed render goes on from the part's feature sums as well as its
// radiance: a resume that renders more gives the features and the denoised
// image of the render that never stopped, bit for bit; a part that holds
// every sample gives its own.
TEST_F(Shards, AResumeKeepsTheFeaturesOfThePart) {
  render("--spp 2 --samples 0:4 --features --out-sum " + f("part.exr") + " --out-denoised " + f("whole.pfm"));
  render("--spp 2 --samples 0:4 --resume " + f("part.exr") + " --out-denoised " + f("again.pfm") +
         " --out-sum " + f("again.exr"));
  EXPECT_EQ(file_bytes(f("whole.pfm")), file_bytes(f("again.pfm")));
  EXPECT_TRUE(read_accumulation(f("again.exr")).with_features);
  // The checkpoints of a render that keeps features keep them too.
  render("--spp 1 --samples 0:4 --features --checkpoint 0 --out-sum " + f("ck.exr"));
  const Accumulation ck = read_accumulation(f("ck.exr")), part = read_accumulation(f("part.exr"));
  EXPECT_TRUE(ck.with_features);
  EXPECT_EQ(ck.features.size(), part.features.size());
  // Four more samples after the part's four: the eight of one render.
  render("--spp 2 --samples 0:8 --features --out-sum " + f("eight.exr") + " --out-denoised " + f("eight.pfm"));
  render("--spp 2 --samples 0:8 --resume " + f("part.exr") + " --features --out-sum " + f("more.exr") +
         " --out-denoised " + f("more.pfm"));
  const Accumulation eight = read_accumulation(f("eight.exr")), more = read_accumulation(f("more.exr"));
  ASSERT_TRUE(more.with_features);
  EXPECT_TRUE(same_bits(eight.sum, more.sum));
  EXPECT_TRUE(same_bits(eight.odd_rgb, more.odd_rgb));
  EXPECT_TRUE(same_bits(eight.features, more.features));
  EXPECT_EQ(file_bytes(f("eight.pfm")), file_bytes(f("more.pfm")));
}
