// A scene's limits follow the machine's memory, not counts: the film, the
// parsed document and the file itself are checked against it before they
// are built, with a message naming the need and the memory.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "scene/scene_io.h"
#include "scene_refusal.h"
#include "scene/scene_memory.h"
#include "run_whisker.h"
#include "sanitized.h"
#include "temp_dir.h"

using namespace whisker;
namespace fs = std::filesystem;

namespace {

std::string camera(long long w, long long h) {
  return R"({"camera": {"width": )" + std::to_string(w) + R"(, "height": )" + std::to_string(h) + "}}";
}

}  // namespace

TEST(SceneMemory, NeedsAreRoundedUpAndTheMachineDown) {
  EXPECT_EQ(memory_text(24ull << 30, false), "24 GB");
  EXPECT_EQ(memory_text((24ull << 30) - 1, false), "23 GB");
  EXPECT_EQ(memory_text((24ull << 30) + 1, true), "25 GB");
  EXPECT_EQ(memory_text(5280000000000ull, true), "4.9 TB");  // 4.802 TiB
  EXPECT_EQ(memory_text(1536ull << 20, true), "1.5 GB");
  EXPECT_EQ(memory_text(900, true), "900 bytes");
  EXPECT_EQ(film_bytes(7680, 4320), 7680ull * 4320 * 132);
  EXPECT_EQ(film_bytes(1ull << 40, 1ull << 40), ~0ull);  // past 2^64: as much as can be said
  EXPECT_EQ(memory_refusal("the film", 24ull << 30, 24ull << 30), "");
  EXPECT_EQ(memory_refusal("200000 x 200000 pixels: the film", film_bytes(200000, 200000), 24ull << 30),
            "200000 x 200000 pixels: the film needs 4.9 TB; this machine has 24 GB");
  EXPECT_GT(machine_memory(), 0u);
}

TEST(SceneMemory, An8KImageIsAccepted) {
  // It was refused as "more than 4096 x 4096"; its film takes 4.4 GB.
  if (machine_memory() < film_bytes(7680, 4320)) GTEST_SKIP() << "less memory than an 8K film";
  Scene s;
  ASSERT_NO_THROW(s = parse_scene(camera(7680, 4320), "8k.json"));
  EXPECT_EQ(s.camera.width, 7680);
  EXPECT_EQ(s.camera.height, 4320);
}

TEST(SceneMemory, AFilmPastTheMachineIsRefusedNamingTheNeedAndTheMemory) {
  const std::string memory = memory_text(machine_memory(), false);
  EXPECT_EQ(scene_refusal(camera(200000, 200000)),
            "bad.json: camera.width: 200000 x 200000 pixels: the film needs " +
                memory_text(film_bytes(200000, 200000), true) + "; this machine has " + memory);
  EXPECT_EQ(scene_refusal(R"({"camera": {"height": 3000000000000}})"),
            "bad.json: camera.height: 512 x 3000000000000 pixels: the film needs " +
                memory_text(film_bytes(512, 3000000000000), true) + "; this machine has " + memory);
  // A side the viewer's texture cannot hold, on a film that fits.
  EXPECT_EQ(scene_refusal(camera(20000, 100)), "bad.json: camera.width: must be in [1, 16384], got 20000");
  // The command line says it the same way, in one line, exit 2.
  const TempDir temp("huge");
  const fs::path p = temp.path() / "huge.json";
  std::ofstream(p) << camera(200000, 200000);
  const Result r = run("--headless --scene " + p.string() + " --frames 1 --out " + p.string() + ".png");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.output, "whisker: " + p.string() + ": camera.width: 200000 x 200000 pixels: the film needs " +
                          memory_text(film_bytes(200000, 200000), true) + "; this machine has " + memory + "\n");
}

TEST(SceneMemory, AMillionSpheresAreRead) {
  // Twelve values and five keys a sphere: it was refused at 4 Mi values.
  const int n = release_or_sanitized(1000000, 100000);
  std::string text = R"({"camera": {"width": 8, "height": 8}, "spheres": [)";
  text.reserve(std::size_t(n) * 80);
  for (int i = 0; i < n; ++i) {
    text += i ? "," : "";
    text += R"({"center":[)" + std::to_string(i % 1000) + "," + std::to_string(i / 1000) +
            R"(,-50],"radius":0.4,"material":{"type":"diffuse","albedo":[0.5,0.5,0.5]}})";
  }
  text += "]}";
  Scene s;
  ASSERT_NO_THROW(s = parse_scene(text, "million.json"));
  ASSERT_EQ(s.spheres.size(), std::size_t(n));
  EXPECT_EQ(s.spheres.back().center, dvec3((n - 1) % 1000, (n - 1) / 1000, -50));
}

TEST(SceneMemory, AFileTooBigForTheMachineIsRefusedFromItsSize) {
  // A sparse file as large as the machine's memory: refused before a byte
  // is read (reading it needs three times its size), in no time.
  const TempDir temp("sparse");
  const fs::path p = temp.path() / "sparse.json";
  std::ofstream(p).put('[');
  std::error_code ec;
  const std::uint64_t size = machine_memory();
  fs::resize_file(p, size, ec);
  if (ec) GTEST_SKIP() << "no sparse file of " << size << " bytes here: " << ec.message();
  const auto start = std::chrono::steady_clock::now();
  std::string what = "(accepted)";
  try {
    load_scene(p);
  } catch (const SceneError& e) {
    what = e.what();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(what, p.string() + ": reading a file of " + memory_text(size, false) + " needs " +
                      memory_text(3 * size, true) + "; this machine has " + memory_text(size, false));
  EXPECT_LT(seconds, 10.0);  // reading 3 x its size would take minutes
}
