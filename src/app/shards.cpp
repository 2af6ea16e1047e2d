#include "app/shards.h"
#include "scene/quote.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

#include "geometry/mesh.h"
#include "io/accumulation_io.h"
#include "io/image_io.h"

#include <sys/resource.h>
#include <sys/sysinfo.h>
#include <unistd.h>

namespace whisker {

namespace {

// The sample index limit of a full render (check_outputs): 2^30.
constexpr std::uint64_t kMaxSample = 1ull << 30;

std::string check_resume(const std::string& path, const Scene& scene, const RenderIdentity& id,
                         Accumulation& acc) {
  try {
    acc = read_accumulation(path);
  } catch (const AccumulationError& e) {
    return std::string("--resume ") + e.what();
  }
  Accumulation here;
  here.width = scene.camera.width;
  here.height = scene.camera.height;
  here.id = id;
  if (const std::string why = identity_mismatch(acc, here); !why.empty())
    return "--resume " + path + ": rendered from other input than this render; differs in " + why +
           " (file vs command line)";
  if (acc.ranges.size() != 1)
    return "--resume " + path + ": holds samples " + ranges_to_string(acc.ranges) +
           ", not one range; resume one contiguous part";
  return {};
}

// With feature buffers asked for (--features, --out-denoised), a resume: a
// part that holds every sample gives its own; a render that goes on cannot
// yet (its film starts from the part's radiance sums alone).
std::string resumed_features(const CommandLine& cl, const ShardPlan& plan) {
  if (!cl.features && cl.out_denoised.empty()) return {};
  const Accumulation& part = *plan.start.resume;
  const std::string option = cl.out_denoised.empty() ? "--features" : "--out-denoised";
  if (!part.with_features)
    return option + " with --resume " + cl.resume + ": the part keeps no feature buffers (render it with --features)";
  return {};
}

}  // namespace

std::uint64_t render_memory(const Scene& scene, bool out_sum, bool resume, bool features) {
  const std::uint64_t pixels = std::uint64_t(scene.camera.width) * std::uint64_t(scene.camera.height);
  // The film's double sums (32), two snapshots of them (32 each), three
  // output images (12 each); with --out-sum the checkpoint's snapshot and
  // its accumulation's copy (the file's writer holds a band of rows); with
  // --resume the part read.
  std::uint64_t per_pixel = 32 + 2 * 32 + 3 * 12;
  if (out_sum) per_pixel += 32 + 32;
  if (resume) per_pixel += 32;
  // Feature buffers: 17 doubles a pixel more in the film and each copy.
  if (features) per_pixel += (out_sum ? 5 : 3) * 136 + (resume ? 136 : 0);
  std::uint64_t bytes = pixels * per_pixel;
  for (const MeshObject& m : scene.meshes)
    if (m.mesh)  // the mesh and about as much again for its BVH and world copy
      bytes += 2 * (m.mesh->positions.size() * sizeof(m.mesh->positions[0]) +
                    m.mesh->triangles.size() * (sizeof(m.mesh->triangles[0]) + 64) +
                    m.mesh->normals.size() * sizeof(m.mesh->normals[0]) +
                    m.mesh->normal_idx.size() * sizeof(m.mesh->normal_idx[0]));
  return bytes;
}

std::string check_memory(const std::string& doing, std::uint64_t bytes) {
  const auto mb = [](std::uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20) + " MB"; };
  struct rlimit lim {};
  if (::getrlimit(RLIMIT_AS, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY) {
    // What is mapped now: the first field of /proc/self/statm, in pages (proc(5)).
    std::uint64_t mapped = 0;
    if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
      unsigned long long pages = 0;
      if (std::fscanf(f, "%llu", &pages) == 1) mapped = pages * std::uint64_t(::sysconf(_SC_PAGESIZE));
      std::fclose(f);
    }
    const std::uint64_t left = lim.rlim_cur > mapped ? lim.rlim_cur - mapped : 0;
    if (bytes > left)
      return "not enough memory for " + doing + ": needs about " + mb(bytes) +
             ", and the memory limit (ulimit -v) leaves " + mb(left);
  }
  struct sysinfo si {};
  if (::sysinfo(&si) == 0) {
    const std::uint64_t total = (std::uint64_t(si.totalram) + si.totalswap) * si.mem_unit;
    if (total > 0 && bytes > total)
      return "not enough memory for " + doing + ": needs about " + mb(bytes) +
             ", and this machine has " + mb(total) + " of RAM and swap";
  }
  return {};
}

std::string plan_shard(const CommandLine& cl, const Scene& scene, ShardPlan& plan) {
  plan = {};
  plan.id = render_identity(scene);
  // --frames N passes of --spp, else the scene's target (samples_per_pixel).
  const std::uint64_t total = samples_per_pixel(cl, scene.settings);
  if (!cl.out_sum.empty() && lower_extension(cl.out_sum) != ".exr")  // x.EXR too, as --out-float
    return "--out-sum " + cl.out_sum + ": must end in .exr";
  if ((!cl.out_sum.empty() || !cl.resume.empty()) && !have_exr())
    return "--out-sum and --resume need OpenEXR, and this build has none";
  SampleRange range{0, total};
  if (!cl.samples.empty()) {
    if (!parse_sample_range(cl.samples, range))
      return "--samples " + cl.samples + ": expected A:B with whole numbers A < B, e.g. 0:512";
    if (range.end > kMaxSample)
      return "--samples " + cl.samples + ": sample indices must stay below 2^30";
  }
  if (cl.resume.empty()) {
    plan.start.first_sample = range.begin;
    plan.target = range.end - range.begin;
    return {};
  }
  auto acc = std::make_shared<Accumulation>();
  if (std::string why = check_resume(cl.resume, scene, plan.id, *acc); !why.empty()) return why;
  const SampleRange done = acc->ranges.front();
  if (cl.samples.empty()) {
    // --frames N: the render of N passes from the part's first sample.
    range = {done.begin, done.begin + total};
  } else if (range.begin != done.begin && range.begin != done.end) {
    // The same command as the interrupted render (A = the part's first
    // sample) or its continuation (A = where the part ends) both go on to B.
    return "--samples " + cl.samples + ": " + cl.resume + " holds samples " +
           ranges_to_string({done}) + ", so the resumed range must start at " +
           std::to_string(done.begin) + " (the same --samples as the part's render) or at " +
           std::to_string(done.end) + " (its continuation)";
  } else {
    range.begin = done.begin;
  }
  if (range.end < done.end)
    return "--resume " + cl.resume + ": already holds samples " + ranges_to_string({done}) +
           ", past the " + std::to_string(range.end - range.begin) + " asked for (--frames x --spp)";
  // A part's header may say anything: the index limit holds for resumed
  // renders too (a range near 2^64 ran the sample counter past 32 bits).
  if (range.end > kMaxSample)
    return "--resume " + cl.resume + ": continuing samples " + ranges_to_string({done}) + " to " +
           std::to_string(range.end) + " passes the sample index limit 2^30";
  plan.start.first_sample = done.begin;
  plan.start.resume = std::move(acc);
  plan.target = range.end - range.begin;
  return resumed_features(cl, plan);
}

Checkpointer::Checkpointer(const ProgressiveRenderer& renderer, std::uint64_t generation,
                           std::string path, double seconds, const ShardPlan& plan)
    : renderer_(renderer), generation_(generation), path_(std::move(path)), seconds_(seconds),
      plan_(plan) {
  if (seconds_ < 0 || path_.empty()) return;
  try {
    thread_ = std::thread([this] { run(); });
  } catch (const std::system_error& e) {  // EAGAIN: ulimit -u or -v
    throw std::runtime_error("--checkpoint: cannot create its thread: " + e.code().message());
  }
}

void Checkpointer::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Checkpointer::run() {
  // Poll the published passes; a pass is written whole or not at all
  // (write_accumulation renames a finished temporary file into place).
  const auto period = std::chrono::duration<double>(std::max(seconds_, 0.05));
  Snapshot snap;
  std::uint64_t written = 0;  // samples in the file
  std::string warned;  // the last failure told, said once (not 19 lines a second on a full disk)
  std::unique_lock lock(mutex_);
  while (!cv_.wait_for(lock, period, [this] { return stopping_; })) {
    if (!renderer_.snapshot(snap) || snap.generation != generation_ || snap.quick ||
        snap.done || snap.spp <= written)
      continue;
    try {
      write_accumulation(path_, accumulation_of(snap, plan_.start.first_sample, plan_.id));
      written = snap.spp;
      warned.clear();
    } catch (const ImageError& e) {
      if (warned != e.what()) std::fprintf(stderr, "whisker: warning: checkpoint: %s\n",
                                          printable(e.what()).c_str());
      warned = e.what();
    }
  }
}

}  // namespace whisker
