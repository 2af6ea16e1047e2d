// The command line's parts that need no parser: its settings applied over
// a scene, the samples a render takes, the nearest-name hints and the
// one-line refusal (cli.h). Apart from cli.cpp, which holds CLI11.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli.h"
#include "scene/quote.h"
#include "scene/scene_io.h"

namespace whisker {

namespace {

// Levenshtein distance, for "did you mean" hints.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string closest(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& c : candidates) {
    if (const std::size_t d = edit_distance(word, c); d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

int usage_error(const std::string& message) {
  // What a message quotes is cut where it is built; this bounds the rest.
  constexpr std::size_t kMax = 4000;
  // Control characters of anything echoed (a path with a line break, an
  // escape sequence in --out) are escaped here, once for every refusal.
  const std::string shown = cut_for_message(message, kMax);
  std::fprintf(stderr, "whisker: %s\n", shown.c_str());
  return kUsageError;
}

std::string apply_command_line(const CommandLine& cl, Scene& scene) {
  for (const SettingField* f : cl.given) copy_field(*f, cl.settings, scene.settings);
  // --mesh replaces the scene's meshes; with none, it would be ignored silently.
  if (!cl.mesh.empty() && scene.meshes.empty())
    return "--mesh " + cut_for_message(cl.mesh) + ": the scene " + cut_for_message(scene.source_path) +
           " has no meshes to replace";
  if (!cl.light.empty()) {
    const auto v = parse_point(cl.light);
    if (!v) return "--light " + cl.light + ": expected three finite numbers x,y,z";
    for (int a = 0; a < 3; ++a)
      if (!(std::fabs((*v)[a]) <= kMaxCoordinate))
        return "--light " + cl.light + ": coordinates must be in [-1e7, 1e7]";
    scene.light.position = *v;
  }
  if (cl.intensity) scene.light.intensity = *cl.intensity;
  return {};
}

bool given(const CommandLine& cl, const char* option) {
  return std::any_of(cl.given.begin(), cl.given.end(),
                     [&](const SettingField* f) { return std::string(f->option) == option; });
}

std::uint64_t samples_per_pixel(const CommandLine& cl, const RenderSettings& s) {
  const std::uint64_t spp = std::uint64_t(std::max(s.spp, 1));
  if (cl.frames > 0) return std::uint64_t(cl.frames) * spp;
  return s.target_spp > 0 ? std::uint64_t(s.target_spp) : spp;
}

}  // namespace whisker
