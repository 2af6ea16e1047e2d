// The estimator's choices for the renderer (render/estimator.h): the quick
// passes' cheap settings, which differ from the settings' own only where
// they are cheaper, and which estimates are deterministic. (render_tile is
// tested beside the paths it traces in lanes, integrator_test.cpp.)
#include <gtest/gtest.h>

#include <vector>

#include "render/estimator.h"

using namespace whisker;

// The quick passes' settings (cheap_settings) differ from the settings' own
// only with more than one sample per pass or with indirect paths split.
TEST(Estimator, QuickPassesOnlyWhenTheyAreCheaper) {
  RenderSettings s;
  s.indirect = false;
  s.spp = 1;
  s.split = {4, 4};
  EXPECT_FALSE(cheap_differs(s));  // splitting needs indirect light
  s.spp = 4;
  EXPECT_TRUE(cheap_differs(s));
  s.spp = 1;
  s.indirect = true;
  EXPECT_TRUE(cheap_differs(s));
  s.split = {1};
  EXPECT_FALSE(cheap_differs(s));
}

// The quick passes' settings: one path per sample (no splitting, unit
// weights), no light connections (a quick pass builds no light cache),
// independent numbers and a seed of their own; the rest as set.
TEST(Estimator, CheapSettingsAreOnePathPerSampleWithASeedOfTheirOwn) {
  RenderSettings s;
  s.spp = 16;
  s.split = {4, 2};
  s.split_weights = vec3(1.0f, 0.5f, 1.0f);
  s.connect = true;
  s.sampler = SamplerKind::Sobol;
  s.indirect = s.aa = s.fresnel = true;
  s.max_depth = 3;
  s.seed = 42;
  const RenderSettings q = cheap_settings(s);
  EXPECT_EQ(q.spp, 1);
  EXPECT_EQ(q.split, std::vector<int>({1}));
  EXPECT_EQ(q.split_weights, vec3(1.0f));
  EXPECT_FALSE(q.connect);
  EXPECT_EQ(q.sampler, SamplerKind::Independent);
  EXPECT_NE(q.seed, s.seed);
  EXPECT_TRUE(q.indirect && q.aa && q.fresnel);
  EXPECT_EQ(q.max_depth, 3);
  EXPECT_FALSE(cheap_differs(q));  // already the cheapest
}

// An estimate is deterministic without indirect light, without jitter and
// without a Fresnel choice: Fresnel on makes a choice only where there is
// glass, a sphere's or a mesh's.
TEST(Estimator, DeterministicWithoutIndirectLightJitterOrAFresnelChoiceAtGlass) {
  Scene scene;
  scene.spheres.push_back({"ball", dvec3(0.0), 1.0f, 0.0f, {MaterialKind::Diffuse, vec3(0.5f)}});
  scene.settings.indirect = scene.settings.aa = false;
  scene.settings.fresnel = true;
  EXPECT_TRUE(deterministic_estimate(scene));  // Fresnel on, but no glass
  Scene jitter = scene;
  jitter.settings.aa = true;
  EXPECT_FALSE(deterministic_estimate(jitter));
  Scene indirect = scene;
  indirect.settings.indirect = true;
  EXPECT_FALSE(deterministic_estimate(indirect));
  Scene glass = scene;
  glass.spheres.push_back({"glass", dvec3(3.0, 0.0, 0.0), 1.0f, 0.0f, {MaterialKind::Glass, vec3(1.0f)}});
  EXPECT_FALSE(deterministic_estimate(glass));
  glass.settings.fresnel = false;  // no choice at the glass: deterministic again
  EXPECT_TRUE(deterministic_estimate(glass));
  Scene hollow_mesh = scene;
  hollow_mesh.meshes.emplace_back();
  hollow_mesh.meshes.back().material.kind = MaterialKind::HollowGlass;
  EXPECT_FALSE(deterministic_estimate(hollow_mesh));
}
