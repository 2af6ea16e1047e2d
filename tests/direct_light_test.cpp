// The direct-light term (render/direct_light.h) on its own: the formula at
// a lit point, points facing away, occluders, and overflow-prone lights.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "render/direct_light.h"
#include "scene/world.h"

using namespace whisker;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The hit record of the point p (world space) of the unit ball, sphere 0 of
// the World (render space, relative to the scene's camera).
SurfaceHit on_ball(const World& world, const vec3& p) {
  SurfaceHit h;
  h.p = world.to_render(p);
  h.err = vec3(glm::dvec3(p) - world.origin() - glm::dvec3(h.p));
  h.ng = h.ns = h.outward = p;
  h.sphere = 0;
  return h;
}

}  // namespace

// The direct-light module on its own: the point light the World owns, the
// formula at a lit point, nothing (and no shadow ray) for a point facing
// away, and nothing behind an occluder (whose shadow ray is counted).
TEST(DirectLight, ThePointLightOfTheWorldAndItsShadow) {
  Scene s;
  s.spheres.push_back({"ball", vec3(0.0f), 1.0f, 0.0f, {MaterialKind::Diffuse, vec3(0.5f)}});
  s.light = {vec3(0.0f, 10.0f, 0.0f), 1000.0f};
  const World world(s);
  const double I = 1000.0;
  for (double deg : {0.0, 30.0, 60.0}) {
    const double a = deg * kPi / 180.0;
    const glm::dvec3 p(std::sin(a), std::cos(a), 0.0), to = glm::dvec3(0, 10, 0) - p;
    const double d2 = glm::dot(to, to), cos_s = glm::dot(p, to) / std::sqrt(d2);
    std::uint64_t rays = 0;
    const LightArrival arrival = direct_light(world, on_ball(world, vec3(p)), {vec3(p), vec3(p)}, rays);
    ASSERT_TRUE(arrival.lit) << deg;
    const float weight = arrival.weight;
    EXPECT_EQ(rays, 1u);
    // I/(4 pi d^2) * <N, w_i> / pi: the albedo is the caller's.
    const double expect = I * cos_s / (4.0 * kPi * kPi * d2);
    EXPECT_NEAR(weight, expect, 1e-5 * expect) << deg;
  }
  std::uint64_t rays = 0;
  const vec3 down(0.0f, -1.0f, 0.0f);
  EXPECT_FALSE(direct_light(world, on_ball(world, down), {down, down}, rays).lit);  // facing away
  EXPECT_EQ(rays, 0u);

  s.spheres.push_back({"blocker", vec3(0.0f, 5.0f, 0.0f), 1.0f, 0.0f, {}});
  const World blocked(s);
  const vec3 up(0.0f, 1.0f, 0.0f);
  EXPECT_FALSE(direct_light(blocked, on_ball(blocked, up), {up, up}, rays).lit);
  EXPECT_EQ(rays, 1u);
}

// I cos / d^2 leaves float's range before the 1/(4 pi^2) brings the term
// back into it (here 1e29 / 1e-10 = 1e39): the term is finite and right, not
// an infinity whose product with a zero channel was a NaN, a dropped sample.
TEST(DirectLight, ABrightLightCloseAboveTheSurfaceIsFiniteAndMatchesTheFormula) {
  Scene s;
  s.spheres.push_back({"ball", vec3(0.0f), 1.0f, 0.0f, {MaterialKind::Diffuse, vec3(0.5f)}});
  s.light = {vec3(0.0f, 1.00001f, 0.0f), 1e29f};
  const World world(s);
  const vec3 up(0.0f, 1.0f, 0.0f);
  const SurfaceHit h = on_ball(world, up);
  // The formula in double, from the render-space floats the term is made of.
  const glm::dvec3 to = glm::dvec3(world.light().position) - glm::dvec3(h.p);
  const double d2 = glm::dot(to, to), cos_s = to.y / std::sqrt(d2);
  const double expect = 1e29 * cos_s / (4.0 * kPi * kPi * d2);
  ASSERT_LT(expect, 3e38);
  ASSERT_GT(1e29 * cos_s / d2, 3.5e38);  // the case: the partial product overflows float
  std::uint64_t rays = 0;
  const LightArrival a = direct_light(world, h, {up, up}, rays);
  ASSERT_TRUE(a.lit);
  EXPECT_NEAR(a.weight, expect, 1e-5 * expect);
}
