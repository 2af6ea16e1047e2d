// Which edits restart the render (viewer/scene_diff.h).
#include <gtest/gtest.h>

#include "viewer/scene_diff.h"
#include "test_scenes.h"

using namespace whisker;

TEST(SceneChange, SameValuesRestartNothing) {
  const Scene a = three_balls();
  Scene b = a;
  EXPECT_EQ(classify_change(a, b), SceneChange::None);
  // A drag that ends where it started, a checkbox clicked twice.
  b.light.position.x += 1.0f;
  b.light.position.x -= 1.0f;
  b.settings.fresnel = !b.settings.fresnel;
  b.settings.fresnel = !b.settings.fresnel;
  EXPECT_EQ(classify_change(a, b), SceneChange::None);
}

TEST(SceneChange, SettingsOnly) {
  const Scene a = three_balls();
  for (auto edit : {+[](RenderSettings& r) { r.spp = 4; },
                    +[](RenderSettings& r) { r.max_depth = 2; },
                    +[](RenderSettings& r) { r.indirect = true; },
                    +[](RenderSettings& r) { r.aa = true; },
                    +[](RenderSettings& r) { r.target_spp = 64; },
                    +[](RenderSettings& r) { r.sampler = SamplerKind::Independent; },
                    +[](RenderSettings& r) { r.zero_cutoff = false; },
                    +[](RenderSettings& r) { r.split = {1}; },
                    +[](RenderSettings& r) { r.split_weights = vec3(1.0f, 0.5f, 1.0f); }}) {
    Scene b = a;
    edit(b.settings);
    EXPECT_EQ(classify_change(a, b), SceneChange::Settings);
  }
}

TEST(SceneChange, SceneEdits) {
  const Scene a = three_balls();
  Scene b = a;
  b.light.intensity *= 2.0f;
  EXPECT_EQ(classify_change(a, b), SceneChange::Scene);
  b = a;
  b.spheres[1].material.ior = 1.33f;
  EXPECT_EQ(classify_change(a, b), SceneChange::Scene);
  b = a;
  b.spheres[0].material.albedo = vec3(0.5f);
  EXPECT_EQ(classify_change(a, b), SceneChange::Scene);
  b = a;
  b.spheres[1].inner_radius = 9.0f;
  EXPECT_EQ(classify_change(a, b), SceneChange::Scene);
  b = a;
  b.camera.fov_deg = 45.0f;
  b.settings.spp = 2;  // a scene change covers settings too
  EXPECT_EQ(classify_change(a, b), SceneChange::Scene);
}
