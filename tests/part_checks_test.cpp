// A part's checks (io/part_checks.h) through the accumulation files'
// reader and merge: every flipped byte, and every flipped bit of an
// uncompressed part, refused or harmless; bands of any height the same file;
// a changed header, another estimator or an old format refused.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "io/accumulation_io.h"
#include "same_bits.h"
#include "temp_dir.h"
#include "test_random.h"

namespace fs = std::filesystem;
using namespace whisker;

namespace {

// A part of `w` x `h` pixels holding samples `range`, its sums varied so
// that every pixel and channel differs.
Accumulation synthetic_part(int w, int h, SampleRange range, unsigned seed) {
  Accumulation a;
  a.width = w;
  a.height = h;
  TestRandom random(seed);
  const auto next = [&] { return random.next(); };
  for (int k = 0; k < 3 * w * h; ++k) a.sum.push_back(next() * 40.0);
  for (int k = 0; k < w * h; ++k) a.sum_sq.push_back(next() * 900.0);
  a.ranges = {range};
  a.counters = {.passes = 1, .nan_count = 3, .rays = 123456789, .seconds = 0.75};
  a.id = {"room", "0123456789abcdef", R"({"aa":true,"seed":0})", estimator_identity()};
  return a;
}

// `a` with feature sums: the odd halves half their wholes, normals negative.
Accumulation with_features(Accumulation a) {
  a.with_features = true;
  for (const double s : a.sum) a.odd_rgb.push_back(s * 0.5);
  for (const double q : a.sum_sq)
    for (int k = 0; k < kFeatureSums; ++k) {
      const int whole = k % 7;
      const bool normal = whole >= 3 && whole < 6;
      a.features.push_back((normal ? -q : q) / (whole + 1) * (k < 7 ? 1.0 : 0.5));
    }
  return a;
}

bool same_merge(const Accumulation& a, const Accumulation& b) {
  return a.width == b.width && a.height == b.height && same_bits(a.sum, b.sum) &&
         same_bits(a.sum_sq, b.sum_sq) && a.with_features == b.with_features &&
         same_bits(a.odd_rgb, b.odd_rgb) && same_bits(a.features, b.features) &&
         a.ranges == b.ranges && a.counters == b.counters &&
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
  const std::string bytes_of = file_bytes(intact);
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

}  // namespace

// Every byte of an 8x6 part flipped in turn (it merged into a wrong image
// once, and into wrong seconds, passes, rays or NaN counts 26 times).
TEST(PartChecksum, EveryFlippedByteIsRefusedOrChangesNothing) {
  const TempDir temp("flip-bytes");
  const fs::path& dir = temp.path();
  const Accumulation part = synthetic_part(8, 6, {4, 8}, 1);
  write_accumulation((dir / "size.exr").string(), part);
  std::vector<std::pair<std::size_t, unsigned char>> flips;
  for (std::size_t at = 0; at < fs::file_size(dir / "size.exr"); ++at) flips.push_back({at, 0xff});
  const int refused = flips_refused_or_harmless(dir, part, flips);
  EXPECT_GT(refused, int(flips.size()) * 3 / 4);
}

// The same with feature layers: a flip in them, in their attribute or in
// their channels' names and types is refused too, or changes nothing.
TEST(PartChecksum, EveryFlippedByteOfAPartWithFeaturesIsRefusedOrChangesNothing) {
  const TempDir temp("flip-features");
  const fs::path& dir = temp.path();
  const Accumulation part = with_features(synthetic_part(4, 3, {3, 8}, 5));
  write_accumulation((dir / "size.exr").string(), part);
  std::vector<std::pair<std::size_t, unsigned char>> flips;
  for (std::size_t at = 0; at < fs::file_size(dir / "size.exr"); ++at) flips.push_back({at, 0xff});
  const int refused = flips_refused_or_harmless(dir, part, flips);
  EXPECT_GT(refused, int(flips.size()) * 3 / 4);
}

// A 1x1 part is stored uncompressed (ZIP would not shrink it): no zlib
// check applies to its words, and single-bit flips in them merged into
// wrong images. Every bit of it flipped in turn.
TEST(PartChecksum, EveryFlippedBitOfAnUncompressedPartIsRefusedOrChangesNothing) {
  const TempDir temp("flip-bits");
  const fs::path& dir = temp.path();
  const Accumulation part = synthetic_part(1, 1, {4, 8}, 2);
  write_accumulation((dir / "size.exr").string(), part);
  std::vector<std::pair<std::size_t, unsigned char>> flips;
  const std::size_t size = fs::file_size(dir / "size.exr");
  for (std::size_t at = 0; at < size; ++at)
    for (int bit = 0; bit < 8; ++bit) flips.push_back({at, (unsigned char)(1u << bit)});
  const int refused = flips_refused_or_harmless(dir, part, flips);
  EXPECT_GT(refused, int(flips.size()) * 3 / 4);
}

// The merge reads each part a band of rows at a time and the writer writes
// one: a height that is not a multiple of the band, bands of one row and
// bands taller than the image give the same file and the same bits.
TEST(PartChecksum, BandsOfAnyHeightGiveTheSameFileAndSums) {
  const TempDir temp("bands");
  const fs::path& dir = temp.path();
  std::vector<NamedAccumulation> parts;
  for (unsigned k = 0; k < 3; ++k) {
    const Accumulation p = synthetic_part(5, 37, {4 * k, 4 * k + 4}, 10 + k);
    const std::string name = (dir / ("p" + std::to_string(k) + ".exr")).string();
    write_accumulation(name, p, 32);
    for (const int band : {1, 4, 7, 37, 100}) {
      write_accumulation((dir / "b.exr").string(), p, band);
      EXPECT_EQ(file_bytes(dir / "b.exr"), file_bytes(name)) << "written in bands of " << band;
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
}

// A part's header fields are the writer's: a changed field, a part from
// another estimator or an older format are refused naming the part.
TEST(PartChecksum, AChangedHeaderAnotherEstimatorOrAnOldFormatIsRefused) {
  const TempDir temp("header");
  const fs::path& dir = temp.path();
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
  const std::string whole = file_bytes(a);
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
}
