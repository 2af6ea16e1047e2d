#include "app/merge.h"

#include <cstdio>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include "app/cli.h"
#include "app/shards.h"
#include "io/accumulation_io.h"
#include "io/image_io.h"
#include "io/stats_io.h"
#include "scene/quote.h"

namespace whisker {

namespace fs = std::filesystem;

namespace {

std::string check_outs(const MergeCommandLine& o) {
  if (o.outs.empty() && o.stats_json.empty())
    return "merge needs at least one --out (.exr, .pfm or .png) or --stats";
  // No output may replace a part or another output (--stats too).
  std::vector<std::string> all;
  for (const std::string& out : o.outs) all.push_back("--out " + out);
  if (!o.stats_json.empty()) all.push_back("--stats " + o.stats_json);
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
  return {};
}

// The accumulation files first (each written a band at a time), then the
// images and stats from the sums taken over (no copy of them).
void write(const MergeCommandLine& o, Accumulation&& acc) {
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
  if (!o.stats_json.empty()) write_stats_json(o.stats_json, {scene, &snap, 0, nullptr, {}});
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
    Accumulation acc = merge_accumulation_files(o.parts, [](const Accumulation& header) {
      const std::size_t pixels = std::size_t(header.width) * std::size_t(header.height);
      if (const std::string why = check_memory("merging", pixels * kMergeBytesPerPixel); !why.empty())
        throw AccumulationError("merge: " + why);
    });
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
