#include "io/stats_io.h"

#include <type_traits>

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "io/image_error.h"
#include "scene/quote.h"
#include "scene/settings_json.h"

namespace whisker {

void write_stats_json(const std::string& path, const RenderStats& st) {
  const Snapshot& snap = *st.snap;
  const double secs = snap.counters.seconds;
  const double samples = double(snap.width) * snap.height * double(snap.spp);
  nlohmann::json j = {
      {"scene", cut_for_message(st.scene)},  // a name of megabytes is not copied whole
      {"width", snap.width},
      {"height", snap.height},
      {"spp", snap.spp},
      {"passes", snap.counters.passes},
      {"generation", snap.generation},
      {"seconds", secs},
      {"passes_per_s", secs > 0 ? double(snap.counters.passes) / secs : 0.0},
      // A sample is one camera ray's estimate; with splitting it continues
      // as several paths, so this counts samples, not paths.
      {"samples_per_s", secs > 0 ? samples / secs : 0.0},
      {"rays", snap.counters.rays},
      {"rays_per_s", secs > 0 ? double(snap.counters.rays) / secs : 0.0},
      {"nan_count", snap.counters.nan_count},
      {"threads", st.threads},
      // A quick pass has no noise estimate; nlohmann writes NaN and Inf as null.
      // The figure is the worst of the scales below (Snapshot).
      {"relative_standard_error", snap.quick ? NAN : snap.relative_standard_error()},
  };
  // Per scale k (box filter side): the pixel figure at 1, the half images'
  // figure times k beyond; equal for independent pixels.
  nlohmann::json by_scale = {{"1", snap.quick ? NAN : snap.pixel_standard_error()}};
  for (int k : kNoiseScales)
    by_scale[std::to_string(k)] = snap.quick ? NAN : snap.scale_standard_error(k);
  j["relative_standard_error_by_scale"] = by_scale;
  if (st.settings) j["settings"] = settings_to_json(*st.settings);
  for (const auto& [key, value] : st.extra)
    std::visit(
        [&, &key = key](const auto& v) {
          if constexpr (std::is_same_v<std::decay_t<decltype(v)>, RenderStats::JsonText>)
            j[key] = nlohmann::json::parse(v.text);
          else
            j[key] = v;
        },
        value);
  // The scene name may come from a file name or a part's header, in any
  // bytes: what is not UTF-8 is written as U+FFFD (dump would throw).
  write_bytes_atomically(path, j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

}  // namespace whisker
