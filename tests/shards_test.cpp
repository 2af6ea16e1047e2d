// Sample-range shards, accumulation files, merge and resume: the whisker
// binary end to end, and the accumulation file format on its own. The
// exactness claims are checked bit for bit: output files byte for byte, sums
// by their bit patterns.
#include <gtest/gtest.h>

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
#include "sanitized.h"

namespace fs = std::filesystem;
using namespace whisker;

namespace {

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// The indirect room at 96x96 with Fresnel glass and anti-aliasing on, so the
// shards go through pixel jitter, splitting (4,4 branches per sample, whose
// Sobol indices are i*K+k of the global sample index i), the Fresnel choice
// and light connections (each pass's shared light paths, read sample-major).
class Shards : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("whisker-shards-" + std::to_string(::getpid()) + "-" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
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
  void TearDown() override { fs::remove_all(dir); }

  // whisker --headless on the small room with `args`; expects success.
  void render(const std::string& args) {
    const Result r = run("--headless --quiet --threads 2 --scene " + scene.string() + " " + args);
    ASSERT_EQ(r.code, 0) << args << "\n" << r.output;
  }
  std::string f(const std::string& name) const { return (dir / name).string(); }

  fs::path dir, scene;
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
    EXPECT_NE(bytes(f("a.pfm")), bytes(f("b.pfm")));
    // Given out of order: the merge folds in range order. (--out takes one
    // value each time, so the parts may follow it.)
    const Result m = run("merge --out " + f("m.pfm") + " " + f("b.exr") + " " + f("a.exr") +
                         " --out " + f("m.exr") + " --out " + f("m.png"));
    ASSERT_EQ(m.code, 0) << m.output;
    EXPECT_NE(m.output.find("samples 0:6"), std::string::npos) << m.output;
    EXPECT_EQ(bytes(f("frames.pfm")), bytes(f("full.pfm")));
    EXPECT_EQ(bytes(f("full.pfm")), bytes(f("m.pfm")));
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
  EXPECT_EQ(bytes(f("full.pfm")), bytes(f("resumed.pfm")));
  EXPECT_EQ(read_accumulation(f("resumed.exr")).ranges, (std::vector<SampleRange>{{0, 6}}));
  // --samples may name the continuation instead of --frames.
  render("--spp 2 --samples 2:6 --resume " + f("part.exr") + " --out-float " + f("r2.pfm"));
  EXPECT_EQ(bytes(f("full.pfm")), bytes(f("r2.pfm")));
  // Resuming a part that already holds every sample writes it as it is.
  render("--spp 2 --frames 3 --resume " + f("resumed.exr") + " --out-float " + f("again.pfm"));
  EXPECT_EQ(bytes(f("full.pfm")), bytes(f("again.pfm")));
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
  EXPECT_EQ(bytes(f("full.pfm")), bytes(f("resumed.pfm")));
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
    const std::string whole = bytes(f("a.exr"));
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
  EXPECT_EQ(bytes(f("full.pfm")), bytes(f("resumed.pfm")));
}

TEST(AccumulationFile, DamagedSumsAndCountersAreRefusedNamingTheField) {
  Accumulation a;
  a.width = 2;
  a.height = 1;
  a.sum = {1, 2, 3, 4, 5, 6};
  a.sum_sq = {1, 2};
  a.ranges = {{0, 4}};
  a.counters.passes = 1;
  a.id = {"room", "0123456789abcdef", R"({"seed":1})", estimator_identity()};
  const fs::path p = fs::temp_directory_path() / ("whisker-bad-" + std::to_string(::getpid()) + ".exr");
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
  fs::remove(p);
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
  const fs::path p = fs::temp_directory_path() / ("whisker-acc-" + std::to_string(::getpid()) + ".exr");
  write_accumulation(p.string(), a);
  const Accumulation b = read_accumulation(p.string());
  fs::remove(p);
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

namespace {

// A part of `w` x `h` pixels holding samples `range`, its sums varied so
// that every pixel and channel differs.
Accumulation synthetic_part(int w, int h, SampleRange range, unsigned seed) {
  Accumulation a;
  a.width = w;
  a.height = h;
  std::uint64_t x = 0x9e3779b97f4a7c15ull * (seed + 1);
  const auto next = [&] {
    x ^= x >> 12, x ^= x << 25, x ^= x >> 27;  // xorshift64* (Marsaglia)
    return double((x * 0x2545f4914f6cdd1dull) >> 11) * 0x1p-53;
  };
  for (int k = 0; k < 3 * w * h; ++k) a.sum.push_back(next() * 40.0);
  for (int k = 0; k < w * h; ++k) a.sum_sq.push_back(next() * 900.0);
  a.ranges = {range};
  a.counters = {.passes = 1, .nan_count = 3, .rays = 123456789, .seconds = 0.75};
  a.id = {"room", "0123456789abcdef", R"({"aa":true,"seed":0})", estimator_identity()};
  return a;
}

bool same_merge(const Accumulation& a, const Accumulation& b) {
  return a.width == b.width && a.height == b.height && same_bits(a.sum, b.sum) &&
         same_bits(a.sum_sq, b.sum_sq) && a.ranges == b.ranges && a.counters == b.counters &&
         a.id.scene == b.id.scene && a.id.scene_hash == b.id.scene_hash &&
         a.id.settings == b.id.settings && a.id.estimator == b.id.estimator;
}

// Flips each of `flips` (byte offset, mask) of the part in turn: the merge
// of the flipped part (and a resume's read of it) either refuses it with
// one line naming it, or gives exactly what the intact part gives (a flip
// in bytes nothing reads). Returns how many were refused.
int flips_refused_or_harmless(const fs::path& dir, const Accumulation& part,
                              const std::vector<std::pair<std::size_t, unsigned char>>& flips) {
  const std::string intact = (dir / "intact.exr").string(), flipped = (dir / "flipped.exr").string();
  write_accumulation(intact, part);
  const Accumulation want = merge_accumulation_files({intact});
  EXPECT_TRUE(same_merge(want, part));
  const std::string bytes_of = bytes(intact);
  int refused = 0, failures = 0;
  for (const auto& [at, mask] : flips) {
    std::string b = bytes_of;
    b[at] = char(b[at] ^ mask);
    std::ofstream(flipped, std::ios::binary | std::ios::trunc) << b;
    for (int reader = 0; reader < 2; ++reader) {
      try {
        const Accumulation got = reader == 0 ? merge_accumulation_files({flipped}) : read_accumulation(flipped);
        if (!same_merge(got, want) && ++failures <= 5)
          ADD_FAILURE() << "byte " << at << " ^ " << int(mask) << ": read into another part ("
                        << (reader == 0 ? "merge" : "resume") << ")";
      } catch (const AccumulationError& e) {
        const std::string m = e.what();
        refused += reader == 0;
        if ((m.find(flipped) == std::string::npos || m.find('\n') != std::string::npos) && ++failures <= 5)
          ADD_FAILURE() << "byte " << at << ": " << m;
      }
    }
  }
  EXPECT_EQ(failures, 0);
  return refused;
}

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("whisker-" + name + "-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

}  // namespace

// Every byte of an 8x6 part flipped in turn (it merged into a wrong image
// once, and into wrong seconds, passes, rays or NaN counts 26 times).
TEST(PartChecksum, EveryFlippedByteIsRefusedOrChangesNothing) {
  const fs::path dir = temp_dir("flip-bytes");
  const Accumulation part = synthetic_part(8, 6, {4, 8}, 1);
  write_accumulation((dir / "size.exr").string(), part);
  std::vector<std::pair<std::size_t, unsigned char>> flips;
  for (std::size_t at = 0; at < fs::file_size(dir / "size.exr"); ++at) flips.push_back({at, 0xff});
  const int refused = flips_refused_or_harmless(dir, part, flips);
  EXPECT_GT(refused, int(flips.size()) * 3 / 4);
  fs::remove_all(dir);
}

// A 1x1 part is stored uncompressed (ZIP would not shrink it): no zlib
// check applies to its words, and single-bit flips in them merged into
// wrong images. Every bit of it flipped in turn.
TEST(PartChecksum, EveryFlippedBitOfAnUncompressedPartIsRefusedOrChangesNothing) {
  const fs::path dir = temp_dir("flip-bits");
  const Accumulation part = synthetic_part(1, 1, {4, 8}, 2);
  write_accumulation((dir / "size.exr").string(), part);
  std::vector<std::pair<std::size_t, unsigned char>> flips;
  const std::size_t size = fs::file_size(dir / "size.exr");
  for (std::size_t at = 0; at < size; ++at)
    for (int bit = 0; bit < 8; ++bit) flips.push_back({at, (unsigned char)(1u << bit)});
  const int refused = flips_refused_or_harmless(dir, part, flips);
  EXPECT_GT(refused, int(flips.size()) * 3 / 4);
  fs::remove_all(dir);
}

// The merge reads each part a band of rows at a time and the writer writes
// one: a height that is not a multiple of the band, bands of one row and
// bands taller than the image give the same file and the same bits.
TEST(PartChecksum, BandsOfAnyHeightGiveTheSameFileAndSums) {
  const fs::path dir = temp_dir("bands");
  std::vector<NamedAccumulation> parts;
  for (unsigned k = 0; k < 3; ++k) {
    const Accumulation p = synthetic_part(5, 37, {4 * k, 4 * k + 4}, 10 + k);
    const std::string name = (dir / ("p" + std::to_string(k) + ".exr")).string();
    write_accumulation(name, p, 32);
    for (const int band : {1, 4, 7, 37, 100}) {
      write_accumulation((dir / "b.exr").string(), p, band);
      EXPECT_EQ(bytes(dir / "b.exr"), bytes(name)) << "written in bands of " << band;
      EXPECT_TRUE(same_merge(read_accumulation(name, band), p)) << "read in bands of " << band;
    }
    parts.push_back({name, p});
  }
  const Accumulation whole = merge_accumulations(parts);
  std::vector<std::string> names = {parts[2].name, parts[0].name, parts[1].name};
  for (const int band : {1, 5, 36, 37, 64}) {
    int headers = 0;
    const Accumulation m = merge_accumulation_files(names, [&](const Accumulation&) { ++headers; }, band);
    EXPECT_TRUE(same_merge(m, whole)) << "merged in bands of " << band;
    EXPECT_EQ(headers, 1);
  }
  fs::remove_all(dir);
}

// A part's header fields are the writer's: a changed field, a part from
// another estimator or an older format are refused naming the part.
TEST(PartChecksum, AChangedHeaderAnotherEstimatorOrAnOldFormatIsRefused) {
  const fs::path dir = temp_dir("header");
  const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
  write_accumulation(a, synthetic_part(4, 3, {0, 4}, 3));
  Accumulation other = synthetic_part(4, 3, {4, 8}, 4);
  other.id.estimator = "whisker 0.0.1 estimator 1";
  write_accumulation(b, other);
  try {
    merge_accumulation_files({a, b});
    ADD_FAILURE() << "parts of two estimators merged";
  } catch (const AccumulationError& e) {
    EXPECT_EQ(std::string(e.what()),
              a + " and " + b + " differ in estimator: \"" + estimator_identity() +
                  "\" vs \"whisker 0.0.1 estimator 1\" (another build)");
  }
  const auto refusal = [](const std::string& path) {
    try {
      read_accumulation(path);
    } catch (const AccumulationError& e) {
      return std::string(e.what());
    }
    return std::string("(read)");
  };
  const std::string whole = bytes(a);
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string d = whole;
    const std::size_t at = d.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) d.replace(at, from.size(), to);
    std::ofstream(b, std::ios::binary | std::ios::trunc) << d;
    return refusal(b);
  };
  // 0:4 to 0:5: the samples the merge would divide by (every pixel 4/5 of itself).
  EXPECT_EQ(replaced("0:4", "0:5").find(b + ": damaged: its header does not match its checksum (crc32 "), 0u);
  EXPECT_EQ(replaced("whisker-accumulation 2", "whisker-accumulation 1"),
            b + ": written by an older whisker (whisker-accumulation 1, without checksums); render it again");
  EXPECT_EQ(replaced("crc32 header", "crc33 header"),
            b + ": whisker.checksum \"crc33 header" + whole.substr(whole.find("crc32 header") + 12, 25) +
                "\" is not \"crc32 header XXXXXXXX pixels XXXXXXXX\"");
  fs::remove_all(dir);
}
