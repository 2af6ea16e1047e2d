// The scene's own questions (src/scene/scene.h): whether its estimate is
// deterministic.
#include <gtest/gtest.h>

#include "scene/scene.h"

using namespace whisker;

// An estimate is deterministic without indirect light, without jitter and
// without a Fresnel choice: Fresnel on makes a choice only where there is
// glass, a sphere's or a mesh's.
TEST(Scene, DeterministicWithoutIndirectLightJitterOrAFresnelChoiceAtGlass) {
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
