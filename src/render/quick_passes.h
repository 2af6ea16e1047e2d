// The viewer's quick passes (ProgressiveRenderer::set_quick_passes): for the first
// moments of every new generation, passes of the quick estimator
// (quick_settings) into a film of their own, so that an edit shows at once.
// They never touch the generation's own accumulation.
#pragma once

#include <cstdint>
#include <memory>

#include "render/camera.h"
#include "render/film.h"
#include "scene/scene.h"

namespace whisker {

// The quick estimator, for the first moments after an edit: the same paths
// at one sample per pass, one path per sample (no splitting), with
// its own seed so its samples are independent of the settings' own.
RenderSettings quick_settings(const RenderSettings& s);
// Whether the quick estimator differs from the settings' own.
bool quick_differs(const RenderSettings& s);

class QuickPasses {
 public:
  // Quick passes run for this long of a generation, before its first pass.
  static constexpr double kSeconds = 0.4;
  // While dragging, a quick pass aims at this long (drag_stride).
  static constexpr double kDragPassSeconds = 0.02;

  // The stride (image pixels per quick pixel, each way) that brings a pass
  // of full_pass_seconds at full resolution under about kDragPassSeconds:
  // 2 before one has been timed, at most 4, and only one dividing the size.
  static int drag_stride(double full_pass_seconds, int width, int height);

  // A new generation: quick passes if `enabled` and the quick estimator
  // differs from the scene's own (a resumed render has none).
  void begin_generation(const Scene& scene, bool enabled);
  // Whether the next pass is a quick one: until kSeconds of them have run
  // or the generation's own first pass (own_spp > 0).
  bool next_is_quick(std::uint64_t own_spp);
  // Before a quick pass: the film at the stride a drag asks for (1 when
  // not dragging), with feature buffers if `features` (at full size only:
  // the denoiser takes no coarse pass). A change of stride starts the quick
  // passes over, as a film holds one resolution.
  void set_up(bool dragging, bool features);

  const Scene& scene() const { return scene_; }
  Film& film() { return film_; }
  // The camera of the quick film: `full` at stride 1.
  const CameraFrame& camera(const CameraFrame& full) const { return stride_ > 1 ? *cam_ : full; }
  std::uint64_t next_sample() const { return spp_; }

  // After a quick pass that took `seconds`: its film into `q`.
  void publish(double seconds, std::uint64_t generation, Snapshot& q);

 private:
  Scene scene_;  // the generation's scene with the quick settings
  Film film_;
  bool active_ = false;
  int stride_ = 0;  // of the film (0: not set up in this generation)
  std::unique_ptr<CameraFrame> cam_;  // the film's camera when stride_ > 1
  std::uint64_t spp_ = 0;
  double seconds_ = 0.0;
  double full_pass_seconds_ = 0.0;  // the latest full-resolution pass's
};

}  // namespace whisker
