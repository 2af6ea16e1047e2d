// Test helper: a fresh, empty directory of a test's own under the system's
// temporary directory, removed with what it holds when the TempDir goes.
// Its name holds a tag, the process id and the running test's name, so
// tests never share one: ctest runs each test in its own process, two at a
// time, and a test binary run by hand runs them one after another in one.
// Also a file's bytes, which the tests compare.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>

#include <unistd.h>

namespace whisker {

class TempDir {
 public:
  // whisker-<tag>-<pid>-<test name>, emptied if a killed run left it.
  explicit TempDir(const std::string& tag) {
    std::string name = "whisker-";
    name += tag;
    name += '-';
    name += std::to_string(::getpid());
    if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info()) {
      name += '-';
      name += info->test_suite_name();
      name += '-';
      name += info->name();
    }
    for (char& c : name)
      if (c == '/') c = '_';  // a parameterised test's name: Suite/Case
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;  // never throw from here; a leftover is harmless
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // The path of `name` inside, as the command line and the writers take it.
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// The whole file, byte for byte ("" if it cannot be read).
inline std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace whisker
