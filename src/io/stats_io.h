// Render statistics as JSON: one writer for the headless --stats file and the
// viewer's summary beside a scripted screenshot.
#pragma once

#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "render/film.h"
#include "scene/settings.h"

namespace whisker {

struct RenderStats {
  std::string scene;
  const Snapshot* snap = nullptr;
  int threads = 0;
  const RenderSettings* settings = nullptr;
  // The caller's own fields (the viewer's window and UI timings; the
  // headless camera and float units). JsonText is written as the JSON it holds.
  struct JsonText {
    std::string text;
  };
  using Value = std::variant<long long, double, std::vector<long long>, std::string, JsonText>;
  std::vector<std::pair<std::string, Value>> extra;
};

// Writes `stats` to `path` through a temporary file; throws ImageError naming
// the path if it cannot. Non-finite numbers are written as null.
void write_stats_json(const std::string& path, const RenderStats& stats);

}  // namespace whisker
