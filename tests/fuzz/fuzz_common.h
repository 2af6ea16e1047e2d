// Shared by the fuzz harnesses: a private temporary folder for the files a
// harness must write (the OBJ loader reads a path, not a string).
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace whisker_fuzz {

// One folder per process, made on first use and removed at exit.
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    std::string tmpl = (std::filesystem::temp_directory_path() / "whisker-fuzz-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) std::abort();
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch_dir(), ec);
    });
    return std::filesystem::path(tmpl);
  }();
  return dir;
}

inline std::filesystem::path write_scratch(const std::string& name, const char* data, std::size_t size) {
  const std::filesystem::path p = scratch_dir() / name;
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(data, static_cast<std::streamsize>(size));
  out.close();
  if (!out) std::abort();  // the scratch folder itself failed: not a finding in Whisker
  return p;
}

// Findings not yet mended are tolerated by the bounded CI run (so it stays
// green) unless WHISKER_FUZZ_STRICT is set; the replay of their reproducers
// sets it. Each tolerance names what it hides.
inline bool strict() { return std::getenv("WHISKER_FUZZ_STRICT") != nullptr; }

}  // namespace whisker_fuzz
