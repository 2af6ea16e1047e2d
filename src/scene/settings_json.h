// RenderSettings to and from a scene file's "settings" object, driven by the
// settings table (scene/settings.h).
#pragma once

#include <nlohmann/json.hpp>

#include "scene/json_fields.h"
#include "scene/settings.h"

namespace whisker {

// Reads every key the table knows into `out` (others are errors naming the
// file and field); keys not present keep their value in `out`.
void read_settings(const Fields& f, RenderSettings& out);
// Every setting, by the table's keys: the scene file's and the stats' block.
nlohmann::json settings_to_json(const RenderSettings& s);

}  // namespace whisker
