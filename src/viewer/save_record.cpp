#include "viewer/save_record.h"

#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "io/render_record.h"
#include "scene/scene_io.h"

namespace whisker {

namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// The objects as a scene file lists them (materials included).
std::string objects_json(const Scene& scene, const std::string& file) {
  const nlohmann::json all = scene_json(scene, file);
  nlohmann::json objects = nlohmann::json::object();
  for (const char* key : {"spheres", "meshes"})
    objects[key] = all.contains(key) ? all[key] : nlohmann::json::array();
  return objects.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

ImageAttributes viewer_record(const ViewerState& s, const Snapshot& own, bool display_units) {
  ImageAttributes a = render_record(s.applied, own, display_units);
  a.emplace_back("whisker.scene_file", s.scene_path);
  a.emplace_back("whisker.objects", objects_json(s.applied, s.scene_path));
  const nlohmann::json edits =
      nlohmann::json::diff(scene_json(s.initial, s.scene_path), scene_json(s.applied, s.scene_path));
  a.emplace_back("whisker.edits", edits.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  // Scene units: the report's white is 255^2.2 radiance.
  const double stops = display_units ? 0.0 : std::log2(double(report_exposure()));
  a.emplace_back("whisker.display_exposure", number(stops));
  a.emplace_back("whisker.display_scale", number(std::exp2(stops)));
  a.emplace_back("whisker.viewer_exposure", number(s.exposure_stops));
  std::string note = "To see what the viewer showed: exposure " + number(stops + s.exposure_stops) +
                     " stops (whisker.display_exposure plus whisker.viewer_exposure), gamma 2.2; "
                     "1.0 after the exposure is the report's white.";
  if (!display_units)
    note += " Values are scene radiance, up to hundreds of thousands: read them as 32-bit "
            "floats (a half float ends at 65504), or save in display units.";
  a.emplace_back("whisker.display_note", note);
  if (showing_denoised(s) && s.display.mode == kViewImage)
    a.emplace_back("whisker.image",
                   "denoised (fast filter) from " + std::to_string(s.denoised.spp) + " spp, not the raw estimate");
  return a;
}

}  // namespace whisker
