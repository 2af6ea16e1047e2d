// Output files and messages under faults: what may be replaced, a failed
// write leaving nothing, the list of temporary files a signal handler
// removes, cut quotes and integer options past their range.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "io/atomic_file.h"
#include "io/image_io.h"
#include "scene/quote.h"
#include "scene/scene_io.h"
#include "scene/settings.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace whisker;

namespace {

std::string write_error(const std::string& path, std::string_view bytes) {
  try {
    write_bytes_atomically(path, bytes);
  } catch (const ImageError& e) {
    return e.what();
  }
  return "(written)";
}

}  // namespace

TEST(OutputFiles, OnlyRegularFilesOrNothingMayBeReplaced) {
  const TempDir temp("out-kinds");
  const fs::path& d = temp.path();
  ASSERT_EQ(::mkfifo((d / "fifo").c_str(), 0600), 0);
  fs::create_directory(d / "dir");
  fs::create_symlink(d / "fifo", d / "link-to-fifo");
  std::ofstream(d / "file") << "old";
  fs::create_symlink(d / "file", d / "link-to-file");
  EXPECT_EQ(not_replaceable((d / "file").string()), "");
  EXPECT_EQ(not_replaceable((d / "missing").string()), "");
  EXPECT_EQ(not_replaceable((d / "link-to-file").string()), "");
  EXPECT_NE(not_replaceable((d / "fifo").string()).find("FIFO"), std::string::npos);
  EXPECT_NE(not_replaceable((d / "link-to-fifo").string()).find("FIFO"), std::string::npos);
  EXPECT_NE(not_replaceable((d / "dir").string()).find("directory"), std::string::npos);
  EXPECT_NE(not_replaceable("/dev/null").find("device"), std::string::npos);

  // The writers refuse too (the viewer's and merge's outputs are checked
  // only here), and the FIFO stays a FIFO.
  const std::string why = write_error((d / "link-to-fifo").string(), "new");
  EXPECT_NE(why.find("link-to-fifo: cannot write: is a FIFO"), std::string::npos) << why;
  EXPECT_TRUE(fs::is_fifo(d / "fifo"));
  EXPECT_TRUE(fs::is_symlink(d / "link-to-fifo"));
  EXPECT_EQ(write_error((d / "file").string(), "new"), "(written)");
  EXPECT_EQ(file_bytes(d / "file"), "new");
}

TEST(OutputFiles, AFailedWriterLeavesNothingBehind) {
  const TempDir temp("out-fail");
  const fs::path& d = temp.path();
  const std::string target = (d / "img.pfm").string();
  std::string tmp_seen;
  try {
    write_file_atomically(target, [&](const std::string& tmp) {
      std::ofstream(tmp) << "half";
      tmp_seen = tmp;
      errno = ENOSPC;
      return false;
    });
    ADD_FAILURE() << "no error";
  } catch (const ImageError& e) {
    EXPECT_EQ(std::string(e.what()), target + ": cannot write: No space left on device");
  }
  // The writer got a name of a fresh file: an unnamed one's /proc link, or
  // ".img.pfm.tmp-" and random letters, not the predictable pid.
  const std::string seen = fs::path(tmp_seen).filename().string();
  EXPECT_TRUE(tmp_seen.rfind("/proc/self/fd/", 0) == 0 ||
              (seen.rfind(".img.pfm.tmp-", 0) == 0 && seen != ".img.pfm.tmp-" + std::to_string(::getpid())))
      << tmp_seen;
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(fs::is_empty(d));
}

TEST(OutputFiles, TemporaryFilesInProgressAreRemovedOnRequest) {
  // What a SIGINT handler does: remove the temporary files being written.
  // An unnamed temporary file (O_TMPFILE) shows nothing in the folder at all;
  // a named one is removed.
  const TempDir temp("out-temps");
  const fs::path& d = temp.path();
  bool existed = false, left = true;
  try {
    write_file_atomically((d / "s.json").string(), [&](const std::string& tmp) {
      std::ofstream(tmp) << "{}";
      existed = fs::exists(tmp);
      remove_temp_files_now();
      left = !fs::is_empty(d);
      return true;
    });
  } catch (const ImageError&) {
    // a named file removed: its rename fails, an error and nothing written
  }
  EXPECT_TRUE(existed);
  EXPECT_FALSE(left);
  for (const auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path().filename(), "s.json");
}

TEST(OutputFiles, TemporaryFilesAreNeverExistingFilesOrLinks) {
  // Every name the writer could pick is taken by a symbolic link to a victim
  // file, as an attacker with write access to the folder could plant: the
  // victim stays as it was and the target is written.
  const TempDir temp("out-links");
  const fs::path& d = temp.path();
  std::ofstream(d / "victim") << "precious";
  for (int pid = 1; pid < 200; ++pid)
    fs::create_symlink(d / "victim", d / (".o.png.tmp-" + std::to_string(::getpid() + pid - 100)));
  write_bytes_atomically((d / "o.png").string(), "new");
  EXPECT_EQ(file_bytes(d / "victim"), "precious");
  EXPECT_EQ(file_bytes(d / "o.png"), "new");
}

TEST(OutputFiles, PngIsWrittenWhole) {
  const TempDir temp("out-png");
  const fs::path& d = temp.path();
  Image img;
  img.width = 3;
  img.height = 2;
  img.rgb.assign(18, 1000.0f);
  write_png((d / "a.png").string(), img);
  const std::string png = file_bytes(d / "a.png");
  ASSERT_GT(png.size(), 20u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(png.size() - 8, 4), "IEND");  // the last chunk, then its CRC
}

TEST(Messages, LongQuotesAreCutAtACharacterBoundary) {
  EXPECT_EQ(cut_for_message("short"), "short");
  EXPECT_EQ(cut_for_message(std::string(300, 'k')), std::string(200, 'k') + "...");
  // "é" is two bytes: a cut inside it keeps neither byte.
  const std::string accents = std::string(199, 'a') + "\xc3\xa9" + "zzz";
  EXPECT_EQ(cut_for_message(accents), std::string(199, 'a') + "...");
}

TEST(Messages, UnknownKeysOfMegabytesAreCut) {
  const std::string key(1 << 20, 'x');
  try {
    parse_scene("{\"" + key + "\": 1}", "big.json");
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_LT(m.size(), 1000u);
    EXPECT_NE(m.find("big.json: " + std::string(200, 'x') + "...: unknown key"), std::string::npos) << m;
  }
}

TEST(Messages, IntegersPastTheirRangeAreReportedAsTyped) {
  RenderSettings s;
  const SettingField& seed = setting_field("seed");
  EXPECT_EQ(set_from_text(seed, "-1", s), "must be in [0, 9007199254740992], got -1");
  EXPECT_EQ(set_from_text(seed, "9007199254740993", s),
            "must be in [0, 9007199254740992], got 9007199254740993");
  EXPECT_EQ(set_from_text(seed, "99999999999999999999", s),
            "must be in [0, 9007199254740992], got 99999999999999999999");
  EXPECT_EQ(set_from_text(seed, "12x", s), "expected an integer");
  EXPECT_EQ(set_from_text(seed, "9007199254740992", s), "");
  EXPECT_EQ(s.seed, 9007199254740992ull);
  EXPECT_EQ(set_from_text(setting_field("spp"), "-99999999999999999999", s),
            "must be in [1, 65536], got -99999999999999999999");
  // A scene file's integer past the signed 64-bit range is not "got -1".
  try {
    parse_scene(R"({"settings": {"spp": 18446744073709551615}})", "s.json");
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("got 18446744073709551615"), std::string::npos) << e.what();
  }
}
