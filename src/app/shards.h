// Sample-range shards and resumed renders on the command line: which samples
// a headless render draws and what its film starts from (docs/SHARDS.md).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

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

// Memory a render or a merge needs, checked before it starts (docs/RELIABILITY.md):
// bytes per pixel of a merge (the merged sums, the mean image, the PFM's
// bytes or the PNG's pixels and stream; the parts are read a band of rows
// at a time, accumulation_io.h).
constexpr std::uint64_t kMergeBytesPerPixel = 32 + 12 + 12;
// With feature buffers: their merged sums, the snapshot's, and the denoiser's
// halves and planes (--out-denoised).
constexpr std::uint64_t kMergeFeatureBytesPerPixel = 136 + 40 * 4 + 64 * 4;
// About how many bytes a headless render of `scene` needs: its image
// buffers (film, published and copied snapshots, output images; more with
// --out-sum and --resume, more with feature buffers) and its meshes with
// their BVH.
std::uint64_t render_memory(const Scene& scene, bool out_sum, bool resume, bool features = false);
// "" if `bytes` more fit under the memory limit (ulimit -v: RLIMIT_AS less
// what the process maps now) and in the machine (RAM and swap); else what
// does not fit, naming `doing` and both figures in MB.
std::string check_memory(const std::string& doing, std::uint64_t bytes);

// --checkpoint: while a headless render runs, writes its latest finished pass
// to the --out-sum file at most every `seconds` (0: after every pass), so a
// render that is killed resumes from there with --resume. A thread of its
// own; stop() before the final outputs are written.
class Checkpointer {
 public:
  Checkpointer(const ProgressiveRenderer& renderer, std::uint64_t generation, std::string path,
               double seconds, const ShardPlan& plan);
  ~Checkpointer() { stop(); }
  Checkpointer(const Checkpointer&) = delete;
  Checkpointer& operator=(const Checkpointer&) = delete;
  void stop();

 private:
  void run();

  const ProgressiveRenderer& renderer_;
  std::uint64_t generation_;
  std::string path_;
  double seconds_;
  const ShardPlan& plan_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace whisker
