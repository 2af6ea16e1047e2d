#include "io/render_record.h"

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "scene/scene_io.h"
#include "scene/settings_json.h"

namespace whisker {

std::uint64_t stands_for_spp(const Scene& scene, const Snapshot& snap) {
  return std::max<std::uint64_t>(snap.spp, std::uint64_t(std::max(0, scene.settings.target_spp)));
}

ImageAttributes render_record(const Scene& scene, const Snapshot& snap, bool display_units) {
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.3f", snap.counters.seconds);
  const nlohmann::json light{
      {"position", {scene.light.position.x, scene.light.position.y, scene.light.position.z}},
      {"intensity", scene.light.intensity}};
  ImageAttributes a{{"whisker.scene", scene.name},
                    {"whisker.units", display_units ? "display: 1.0 = 255^2.2 radiance, the report's white"
                                                    : "scene: radiance, light intensity applied"},
                    {"whisker.spp", std::to_string(snap.spp)},
                    {"whisker.passes", std::to_string(snap.counters.passes)},
                    {"whisker.seed", std::to_string(scene.settings.seed)},
                    {"whisker.seconds", seconds},
                    {"whisker.camera", camera_json(scene.camera).dump()},
                    {"whisker.light", light.dump()},
                    {"whisker.settings", settings_to_json(scene.settings).dump()}};
  if (deterministic_estimate(scene)) {
    a.emplace_back("whisker.exact", "true");
    a.emplace_back("whisker.stands_for_spp", std::to_string(stands_for_spp(scene, snap)));
  }
  return a;
}

}  // namespace whisker
