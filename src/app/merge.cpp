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

void write(const MergeCommandLine& o, const Accumulation& acc) {
  const Snapshot snap = snapshot_of(acc);
  const Image img = mean_image(snap);
  for (const std::string& out : o.outs) {
    const auto ext = lower_extension(out);
    if (ext == ".exr") write_accumulation(out, acc);
    else if (ext == ".pfm") write_pfm(out, img);
    else write_png(out, img);
  }
  if (!o.stats_json.empty()) write_stats_json(o.stats_json, {acc.id.scene, &snap, 0, nullptr, {}});
}

}  // namespace

int run_merge(int argc, char** argv) {
  MergeCommandLine o;
  if (const auto rc = parse_merge_command_line(argc, argv, o)) return *rc;
  if (o.parts.empty())
    return usage_error("merge: no parts given; usage: whisker merge PART.exr... --out FILE");
  if (const std::string why = check_outs(o); !why.empty()) return usage_error(why);
  try {
    // Headers first (checked against each other), then one part's sums at a
    // time added into one sum: memory for two parts' sums whatever their
    // number (8 parts of 4096 x 4096 held 4.7 GB at once).
    std::vector<NamedAccumulation> parts;
    for (const std::string& p : o.parts) parts.push_back({p, read_accumulation_header(p)});
    std::vector<std::size_t> order;
    Accumulation acc = plan_merge(parts, order);
    const std::size_t pixels = std::size_t(acc.width) * std::size_t(acc.height);
    // The sum, one part and its words as read, then the outputs' copies.
    if (const std::string why = check_memory("merging", pixels * kMergeBytesPerPixel); !why.empty())
      return usage_error("merge: " + why);
    for (const std::size_t i : order) {
      const Accumulation part = read_accumulation(parts[i].name);
      if (identity_mismatch(part, parts[i].acc) != "" || part.ranges != parts[i].acc.ranges)
        throw AccumulationError(parts[i].name + ": changed while the merge read it");
      add_sums(acc, part);
    }
    if (const auto gaps = missing_ranges(acc.ranges); !gaps.empty()) {
      const std::string msg = "merge: samples " + ranges_to_string(gaps) +
                              " are missing (the parts hold " + ranges_to_string(acc.ranges) + ")";
      if (!o.partial) return usage_error(msg + "; render them, or pass --partial");
      std::fprintf(stderr, "whisker: warning: %s; writing the partial merge\n", printable(msg).c_str());
    }
    write(o, acc);
    std::printf("%s %dx%d: merged %zu part%s, samples %s (%llu spp, %llu passes)\n",
                printable(acc.id.scene).c_str(), acc.width, acc.height, o.parts.size(),
                o.parts.size() == 1 ? "" : "s",
                ranges_to_string(acc.ranges).c_str(), (unsigned long long)acc.samples(),
                (unsigned long long)acc.counters.passes);
    return 0;
  } catch (const std::bad_alloc&) {
    return usage_error("merge: out of memory while merging the parts");
  } catch (const std::exception& e) {
    return usage_error(e.what());
  }
}

}  // namespace whisker
