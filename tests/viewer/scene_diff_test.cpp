// Which edits restart the render (viewer/scene_diff.h).
#include <gtest/gtest.h>

#include <algorithm>

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
  Scene a = three_balls();
  a.settings.indirect = true;  // which splitting and its weights act on
  for (auto edit : {+[](RenderSettings& r) { r.spp = 4; },
                    +[](RenderSettings& r) { r.max_depth = 2; },
                    +[](RenderSettings& r) { r.indirect = false; },
                    +[](RenderSettings& r) { r.connect = !r.connect; },
                    +[](RenderSettings& r) { r.fresnel = !r.fresnel; },
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

// Settings that cannot change this scene's image are applied without a
// restart: Fresnel where nothing is glass; splitting, its weights and light
// connections without indirect light. With glass, Fresnel restarts.
TEST(SceneChange, SettingsThatCannotChangeTheImageRestartNothing) {
  Scene plain = three_balls();
  plain.spheres.erase(std::remove_if(plain.spheres.begin(), plain.spheres.end(),
                                     [](const SphereObject& s) { return is_glass(s.material.kind); }),
                      plain.spheres.end());
  ASSERT_FALSE(has_glass(plain));
  Scene b = plain;
  b.settings.fresnel = !b.settings.fresnel;
  EXPECT_EQ(classify_change(plain, b), SceneChange::Inert);
  b.settings.aa = !b.settings.aa;  // and one that does change it
  EXPECT_EQ(classify_change(plain, b), SceneChange::Settings);
  const Scene glass = three_balls();
  ASSERT_TRUE(has_glass(glass));
  b = glass;
  b.settings.fresnel = !b.settings.fresnel;
  EXPECT_EQ(classify_change(glass, b), SceneChange::Settings);
  ASSERT_FALSE(glass.settings.indirect);
  for (auto edit : {+[](RenderSettings& r) { r.split = {8, 2}; },
                    +[](RenderSettings& r) { r.split_weights = vec3(1.0f, 0.5f, 1.0f); },
                    +[](RenderSettings& r) { r.connect = !r.connect; }}) {
    b = glass;
    edit(b.settings);
    EXPECT_EQ(classify_change(glass, b), SceneChange::Inert);
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
