#include "app/merge.h"

#include <cstdio>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli.h"
#include "app/denoised_output.h"
#include "app/shards.h"
#include "io/accumulation_io.h"
#include "io/image_io.h"
#include "io/stats_io.h"
#include "scene/quote.h"

namespace whisker {

namespace fs = std::filesystem;

namespace {

std::string check_outs(const MergeCommandLine& o) {
  if (o.outs.empty() && o.stats_json.empty() && o.out_denoised.empty())
    return "merge needs at least one --out (.exr, .pfm or .png), --out-denoised or --stats";
  // No output may replace a part or another output (--stats too).
  std::vector<std::string> all;
  for (const std::string& out : o.outs) all.push_back("--out " + out);
  if (!o.stats_json.empty()) all.push_back("--stats " + o.stats_json);
  if (!o.out_denoised.empty()) all.push_back("--out-denoised " + o.out_denoised);
  const auto path_of = [](const std::string& a) { return a.substr(a.find(' ') + 1); };
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (std::size_t j = i + 1; j < all.size(); ++j)
      if (same_file(path_of(all[i]), path_of(all[j])))
        return "merge " + all[i] + " and " + all[j] + " name the same file; give each output its own";
    for (const std::string& part : o.parts)
      if (same_file(path_of(all[i]), part))
        return "merge " + all[i] + ": is one of the parts; write the merge elsewhere";
  }
  for (const std::string& out : o.outs) {
    const auto ext = lower_extension(out);  // x.PNG too, as in a render
    if (ext != ".exr" && ext != ".pfm" && ext != ".png")
      return "merge --out " + out + ": must end in .exr (accumulation), .pfm or .png";
    if (ext == ".exr" && !have_exr()) return "merge --out " + out + ": this build has no OpenEXR";
    for (const std::string& part : o.parts) {
      std::error_code ec;
      if (fs::equivalent(out, part, ec))
        return "merge --out " + out + ": is one of the parts; write the merge elsewhere";
    }
  }
  if (!o.out_denoised.empty()) {
    const auto ext = lower_extension(o.out_denoised);
    if (ext != ".png" && ext != ".pfm" && ext != ".exr")
      return "merge --out-denoised " + o.out_denoised + ": must end in .png, .pfm or .exr";
    if (ext == ".exr" && !have_exr()) return "merge --out-denoised " + o.out_denoised + ": this build has no OpenEXR";
  }
  return {};
}

// What the parts' settings say of the denoised copy: an estimate that is
// exact whatever the scene (no indirect light, no anti-aliasing, no Fresnel
// choice) is its own copy, as a render's; independent numbers give
// independent halves, whose estimate of the error holds.
DenoisedOutput denoised_output(const MergeCommandLine& o, const Accumulation& acc) {
  const nlohmann::json s = nlohmann::json::parse(acc.id.settings, nullptr, false);
  const auto off = [&](const char* key) { return s.is_object() && s.value(key, true) == false; };
  DenoisedOutput out;
  out.path = o.out_denoised;
  out.fast = o.denoiser == "fast";
  out.exact = off("indirect") && off("aa") && off("fresnel");
  out.independent = s.is_object() && s.value("sampler", std::string()) == "independent";
  out.attributes = {{"whisker.scene", acc.id.scene},
                    {"whisker.units", "scene: radiance, light intensity applied"},
                    {"whisker.spp", std::to_string(acc.samples())},
                    {"whisker.samples", ranges_to_string(acc.ranges)},
                    {"whisker.passes", std::to_string(acc.counters.passes)},
                    {"whisker.settings", acc.id.settings}};
  return out;
}

// Why the merge of `header` (sums empty) cannot be denoised, or "".
std::string cannot_denoise(const MergeCommandLine& o, const Accumulation& header, const std::string& dropped) {
  if (o.out_denoised.empty() || denoised_output(o, header).exact) return {};
  const std::string option = "merge --out-denoised " + o.out_denoised + ": ";
  if (!dropped.empty()) return option + dropped;
  if (!header.with_features)
    return option + "the parts keep no feature buffers (render them with --features or --out-denoised)";
  if (header.ranges.size() != 1)
    return option + "the merge holds samples " + ranges_to_string(header.ranges) +
           ", not one range (the half images need every sample from the first)";
  if (header.samples() < 2) return option + "it needs at least 2 samples per pixel (one in each half)";
  return {};
}

// The accumulation files first (each written a band at a time), then the
// images and stats from the sums taken over (no copy of them).
void write(const MergeCommandLine& o, Accumulation&& acc) {
  const DenoisedOutput denoised = denoised_output(o, acc);
  for (const std::string& out : o.outs)
    if (lower_extension(out) == ".exr") write_accumulation(out, acc);
  const std::string scene = acc.id.scene;
  const Snapshot snap = snapshot_of(std::move(acc));
  Image img;
  for (const std::string& out : o.outs) {
    const auto ext = lower_extension(out);
    if (ext == ".exr") continue;
    if (img.rgb.empty()) img = mean_image(snap);
    if (ext == ".pfm") write_pfm(out, img);
    else write_png(out, img);
  }
  RenderStats stats{scene, &snap, 0, nullptr, {}};
  if (!o.out_denoised.empty()) {
    if (img.rgb.empty()) img = mean_image(snap);
    const std::string rec = write_denoised(denoised, snap, img);
    stats.extra.emplace_back("denoised", RenderStats::JsonText{rec});
  }
  if (!o.stats_json.empty()) write_stats_json(o.stats_json, stats);
}

}  // namespace

int run_merge(int argc, char** argv) {
  MergeCommandLine o;
  if (const auto rc = parse_merge_command_line(argc, argv, o)) return *rc;
  if (o.parts.empty())
    return usage_error("merge: no parts given; usage: whisker merge PART.exr... --out FILE");
  if (const std::string why = check_outs(o); !why.empty()) return usage_error(why);
  try {
    // Headers first (checked against each other), then each part's sums a
    // band of rows at a time into one sum: memory for one image's sums
    // whatever the parts' number (8 parts of 4096 x 4096 held 4.7 GB at
    // once, then 1.5 GB with a whole part at a time).
    std::string dropped;  // a part without feature buffers beside parts with them
    const auto before_sums = [&](const Accumulation& header) {
      if (const std::string why = cannot_denoise(o, header, dropped); !why.empty()) throw AccumulationError(why);
      const std::size_t pixels = std::size_t(header.width) * std::size_t(header.height);
      const std::uint64_t per_pixel =
          kMergeBytesPerPixel + (header.with_features ? kMergeFeatureBytesPerPixel : 0);
      if (const std::string why = check_memory("merging", pixels * per_pixel); !why.empty())
        throw AccumulationError("merge: " + why);
      if (!dropped.empty())
        std::fprintf(stderr, "whisker: warning: merge: %s; the merge keeps none\n", printable(dropped).c_str());
    };
    Accumulation acc = merge_accumulation_files(o.parts, before_sums, kBandRows, &dropped);
    if (const auto gaps = missing_ranges(acc.ranges); !gaps.empty()) {
      const std::string msg = "merge: samples " + ranges_to_string(gaps) +
                              " are missing (the parts hold " + ranges_to_string(acc.ranges) + ")";
      if (!o.partial) return usage_error(msg + "; render them, or pass --partial");
      std::fprintf(stderr, "whisker: warning: %s; writing the partial merge\n", printable(msg).c_str());
    }
    char line[256];
    std::snprintf(line, sizeof line, "%dx%d: merged %zu part%s, samples ", acc.width, acc.height,
                  o.parts.size(), o.parts.size() == 1 ? "" : "s");
    const std::string summary = printable(acc.id.scene) + " " + line + ranges_to_string(acc.ranges) +
                                " (" + std::to_string(acc.samples()) + " spp, " +
                                std::to_string(acc.counters.passes) + " passes)";
    write(o, std::move(acc));
    std::printf("%s\n", summary.c_str());
    return 0;
  } catch (const std::bad_alloc&) {
    return usage_error("merge: out of memory while merging the parts");
  } catch (const std::exception& e) {
    return usage_error(e.what());
  }
}

}  // namespace whisker
