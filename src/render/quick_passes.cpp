#include "render/quick_passes.h"

#include <algorithm>
#include <cmath>


namespace whisker {

bool quick_differs(const RenderSettings& s) {
  if (s.spp > 1) return true;
  if (!s.indirect) return false;  // splitting acts on indirect paths only
  for (int f : s.split)
    if (f > 1) return true;
  return false;
}

RenderSettings quick_settings(const RenderSettings& s) {
  RenderSettings q = s;
  q.spp = 1;
  q.split = {1};
  q.split_weights = vec3(1.0f);
  // Light connections need the light cache a quick pass does not build.
  q.connect = false;
  // The cheapest numbers: a quick pass is one sample per pixel, where the
  // Sobol points' stratification over a pixel's samples has little to give,
  // and drawing them is a noticeable part of a one-sample pass.
  q.sampler = SamplerKind::Independent;
  // Samples independent of the generation's own (which use `seed`).
  q.seed = s.seed ^ 0x9e3779b97f4a7c15ull;
  return q;
}

int QuickPasses::drag_stride(double full_pass_seconds, int width, int height) {
  // A pass's time goes with its pixel count, 1 / stride^2.
  int stride = 2;
  if (full_pass_seconds > 0.0) stride = int(std::ceil(std::sqrt(full_pass_seconds / kDragPassSeconds)));
  stride = std::clamp(stride, 1, 4);
  while (stride > 1 && (width % stride != 0 || height % stride != 0)) --stride;
  return stride;
}

void QuickPasses::begin_generation(const Scene& scene, bool enabled) {
  active_ = enabled && quick_differs(scene.settings);
  stride_ = 0;
  spp_ = 0;
  seconds_ = 0.0;
  if (!active_) return;
  scene_ = scene;
  scene_.settings = quick_settings(scene.settings);
}

bool QuickPasses::next_is_quick(std::uint64_t own_spp) {
  if (active_ && (seconds_ >= kSeconds || own_spp > 0)) active_ = false;
  return active_;
}

void QuickPasses::set_up(bool dragging, bool features) {
  const Camera& c = scene_.camera;
  const int stride = dragging ? drag_stride(full_pass_seconds_, c.width, c.height) : 1;
  if (stride == stride_) return;
  stride_ = stride;
  spp_ = 0;
  seconds_ = 0.0;
  if (stride > 1) {
    Camera coarse = c;  // the same image plane, stride times fewer pixels each way
    coarse.width /= stride;
    coarse.height /= stride;
    cam_ = std::make_unique<CameraFrame>(coarse);
  }
  film_.reset(c.width / stride, c.height / stride, features && stride == 1);
}

void QuickPasses::publish(double seconds, std::uint64_t generation, Snapshot& q) {
  spp_ += 1;
  seconds_ += seconds;
  if (stride_ == 1) full_pass_seconds_ = seconds;
  film_.publish(q);
  q.spp = spp_;
  q.first_sample = 0;
  q.generation = generation;
  q.version += 1;
  q.counters = {.passes = spp_, .seconds = seconds_};
  q.done = false;
  q.quick = true;
  q.stride = stride_;
}

}  // namespace whisker
