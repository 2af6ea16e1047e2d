// Sample-range shards and resumed renders on the command line: which samples
// a headless render draws and what its film starts from (docs/SHARDS.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "app/cli.h"
#include "render/progressive.h"

namespace whisker {

// What a headless render does: start, and how many samples per pixel its
// film holds at the end (counting a resumed part's).
struct ShardPlan {
  RenderStart start;
  std::uint64_t target = 0;
  RenderIdentity id;
  // A resumed part that already holds every sample asked for: nothing to render.
  bool complete() const { return start.resume && start.resume->samples() >= target; }
};

// Checks --samples, --resume and --out-sum against each other and the scene,
// reading the resumed file; returns what is wrong ("" if nothing), a line
// naming the option or file and the field.
std::string plan_shard(const CommandLine& cl, const Scene& scene, ShardPlan& plan);

}  // namespace whisker
