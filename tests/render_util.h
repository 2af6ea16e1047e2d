// Test helper: render a scene to its target samples per pixel and return the
// final snapshot, through the same ProgressiveRenderer the app uses.
#pragma once

#include <gtest/gtest.h>

#include "render/progressive.h"

namespace whisker {

inline Snapshot render(const Scene& scene, int threads = 0) {
  ProgressiveRenderer r(threads);
  const auto gen = r.set_scene(scene);
  r.start();
  EXPECT_TRUE(r.wait_for(gen, std::uint64_t(scene.settings.target_spp)));
  Snapshot s;
  r.snapshot(s);
  r.stop();
  return s;
}

}  // namespace whisker
