// Light connections (render/light_connect.h): the weights of the two ways to
// make a path sum to 1; with them on, every pixel keeps its expectation (a
// closed form inside a sphere; the per-pixel images of the cat's room and
// of the room with glass and a mirror, with splitting;
// a light exactly on a wall); and they do what they are for, less noise in
// the cat's room.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "render/light_connect.h"
#include "scene/scene_io.h"
#include "closed_sphere.h"
#include "render_util.h"

using namespace whisker;

namespace {

// The cat scene (or another bundled one) at a small size, fov narrowed by
// `zoom` so that a pixel covers what one of the 512 x 512 image does.
Scene small(const char* name, int size, int spp, bool connect, std::uint64_t seed,
            float zoom = 1.0f) {
  Scene s = load_scene(resolve_scene(name));
  s.camera.width = s.camera.height = size;
  s.camera.fov_deg = float(2.0 * std::atan(std::tan(s.camera.fov_deg * kPi / 360.0) / zoom) * 360.0 / kPi);
  s.settings.spp = s.settings.target_spp = spp;
  s.settings.connect = connect;
  s.settings.seed = seed;
  return s;
}

}  // namespace

// One path camera -> x -> y -> light, x and y on two walls at right angles:
// the bounce's weight, from what the bounce sees at y (its departure cosine,
// its distance and y's normal), and the light path's, from the two points,
// sum to 1 for every split count; and A and B are the densities per area
// the header gives, up to pi (checked against their definitions in double).
TEST(LightConnect, WeightsOfOnePathSumToOne) {
  const vec3 light(0.3f, 4.0f, 2.5f);
  int checked = 0;
  for (int k = 0; k < 50; ++k) {
    const vec3 x(0.2f + 0.07f * float(k), 0.0f, 1.0f + 0.03f * float(k));  // on the floor y = 0
    const vec3 yp(-1.0f + 0.05f * float(k), 2.0f - 0.03f * float(k), 0.0f);  // on the wall z = 0
    const vec3 nx(0, 1, 0), ny(0, 0, 1);
    const vec3 w = glm::normalize(yp - x);
    const float r2 = glm::dot(yp - x, yp - x);
    const vec3 to_light = light - yp;
    const float d2 = glm::dot(to_light, to_light);
    const float cos_l = glm::dot(ny, to_light) / std::sqrt(d2);
    for (int n : {1, 2, 4, 16}) {
      // The light cache's density factor M / M_c (light_cache.h).
      const float scale = n == 2 ? 3.5f : 1.0f;
      // The bounce's side: a ray from x along w meets y at distance r.
      const Departure from = departure(FacingNormals(nx, nx), w, n, scale);
      SurfaceHit y;
      y.t = std::sqrt(r2);
      y.ng = ny;
      y.p = yp;
      Ray in;
      in.d = w;
      const LightArrival a{true, 1.0f, cos_l, d2};
      const float wb = bounce_weight(from, in, y, a, 0.0f);
      // The light path's side, as light_connection forms it.
      const float A = glm::dot(nx, w) * -glm::dot(ny, w) / r2;
      const float B = cos_l / (4.0f * d2);
      const float wl = light_path_factor(float(n), A, scale * B) * (scale * B / A);
      EXPECT_NEAR(wb + wl, 1.0f, 1e-5f) << k << " n " << n;
      // A = pi p_b (cos_x / pi cos_y / r^2), B = pi p_l (cos_l / (4 pi d^2)).
      const double pb = glm::dot(glm::dvec3(nx), glm::dvec3(w)) / kPi * glm::dot(glm::dvec3(ny), -glm::dvec3(w)) / double(r2);
      const double pl = double(cos_l) / (4.0 * kPi * double(d2));
      EXPECT_NEAR(A, kPi * pb, 1e-5 * kPi * pb);
      EXPECT_NEAR(B, kPi * pl, 1e-5 * kPi * pl);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 200);
}

// Where no light path can make the bounce's path, the bounce takes it all:
// no light path sent from x (cos 0), and y closer to the light than light
// paths start.
TEST(LightConnect, BounceWeightIsOneWhereNoLightPathReaches) {
  SurfaceHit y;
  y.t = 2.0f;
  y.ng = vec3(0, 0, 1);
  Ray in;
  in.d = vec3(0, 0, -1);
  const LightArrival a{true, 1.0f, 1.0f, 1.0f};
  EXPECT_EQ(bounce_weight(Departure{}, in, y, a, 0.0f), 1.0f);
  EXPECT_LT(bounce_weight(Departure{1.0f, 1.0f}, in, y, a, 0.0f), 1.0f);
  EXPECT_EQ(bounce_weight(Departure{1.0f, 1.0f}, in, y, a, 2.0f), 1.0f);
  // A bounce whose direction is behind x's geometric normal cannot be made
  // by a light path (vertex normals): no departure.
  EXPECT_EQ(departure(FacingNormals(vec3(0, 0, 1), glm::normalize(vec3(1, 0, 1))),
                      glm::normalize(vec3(1, 0, -0.1f)), 4).cos, 0.0f);
}

// A light off the centre of a closed diffuse sphere (radius R, albedo rho):
// at the first hit y,
//   L(y) = rho/pi [I cos/|c-y|^2 + (I/R^2) rho (1 - rho^(B-1))/(1 - rho)] / (4 pi)
// (a cosine-sampled direction inside a sphere lands uniformly on its area;
// integrator tests), B = depth + 1. With light connections each pixel mean
// sits within a few standard errors of it, for one path per sample,
// splitting and the independent sampler.
struct ConnectCase {
  std::vector<int> split;
  SamplerKind sampler;
};
class ConnectClosedSphere : public ::testing::TestWithParam<ConnectCase> {};

INSTANTIATE_TEST_SUITE_P(Estimators, ConnectClosedSphere,
                         ::testing::Values(ConnectCase{{1}, SamplerKind::Sobol},
                                           ConnectCase{{4, 2}, SamplerKind::Sobol},
                                           ConnectCase{{3, 2}, SamplerKind::Independent}),
                         [](const auto& info) {
                           std::string name = to_string(info.param.sampler);
                           for (int k : info.param.split) name += "Split" + std::to_string(k);
                           return name;
                         });

TEST_P(ConnectClosedSphere, OffCentreLightKeepsTheClosedForm) {
  const double rho = 0.5, I = 1000.0, R = 10.0;
  const glm::dvec3 c(3.0, -2.0, 1.0);
  int paths = 1;
  for (int k : GetParam().split) paths *= k;
  for (int depth : {1, 3}) {
    const int size = 6, spp = 2048 / paths;
    Scene scene = closed_sphere(float(rho), vec3(c), depth, spp, size);
    RenderSettings& st = scene.settings;
    st.connect = true;
    st.split = GetParam().split;
    st.sampler = GetParam().sampler;
    expect_closed_form(render(scene), scene, ClosedSphereLight{rho, I, R, c},
                       "depth " + std::to_string(depth));
  }
}

// The cat's room (its own split 4,2 with channel weights), on against off:
// the same expectation in every pixel of a view of the whole room.
TEST(LightConnect, CatRoomKeepsEachPixelsExpectation) {
  expect_same_expectation(render(small("cat", 20, 96, false, 11)),
                          render(small("cat", 20, 96, true, 22)), "cat");
}

// The same room's whole image, channel by channel: the means of four
// renders with connections and four without (independent seeds) agree to
// within a few of their standard errors. A pixel's test above cannot see a
// bias of a few percent in one channel (its noise is larger); the image
// mean, from 65536 samples a render, can: its standard error is about 0.3 %.
// Most of the room's vertices are on walls seen from the room, whose own
// entries they leave out (light_cache.h).
TEST(LightConnect, CatRoomKeepsEachChannelsImageMean) {
  std::vector<glm::dvec3> means[2];
  for (int on = 0; on < 2; ++on)
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      const Snapshot s = render(small("cat", 32, 64, on == 1, 100 * std::uint64_t(on) + seed));
      glm::dvec3 m(0.0);
      for (std::size_t p = 0; p < s.sum.size() / 3; ++p)
        m += glm::dvec3(s.sum[3 * p], s.sum[3 * p + 1], s.sum[3 * p + 2]);
      means[on].push_back(m / double(s.sum.size() / 3) / double(s.spp));
    }
  for (int c = 0; c < 3; ++c) {
    double mu[2], var[2];
    for (int on = 0; on < 2; ++on) {
      mu[on] = var[on] = 0.0;
      for (const glm::dvec3& m : means[on]) mu[on] += m[c] / 4.0;
      for (const glm::dvec3& m : means[on]) var[on] += (m[c] - mu[on]) * (m[c] - mu[on]) / 3.0;
    }
    const double se = std::sqrt(var[0] / 4.0 + var[1] / 4.0);
    ASSERT_GT(se, 0.0) << c;
    EXPECT_LT(se, 0.01 * mu[0]) << c;  // the test can see a percent
    EXPECT_LT(std::abs(mu[1] - mu[0]) / se, 5.0) << "channel " << c << ": " << mu[0] << " off, " << mu[1] << " on";
  }
}

// Glass and a mirror: bounces that pass them are the bounce's alone, and
// connections through glass are blocked, as its shadow rays are.
TEST(LightConnect, GlassAndMirrorRoomKeepsEachPixelsExpectation) {
  Scene off = small("indirect", 20, 96, false, 11), on = small("indirect", 20, 96, true, 22);
  off.settings.split = on.settings.split = {2, 2};
  expect_same_expectation(render(off), render(on), "indirect");
}

// A light exactly on top of a white ball in the cat's room, a convex sphere
// seen from the room: light paths into the ball start past the light
// (light_path_start) and meet its inside near the light, which no point of
// the room may see through the ball. The image keeps its expectation, every
// sample finite.
TEST(LightConnect, LightExactlyOnABallKeepsEachPixelsExpectation) {
  Scene off = small("cat", 20, 64, false, 11), on = small("cat", 20, 64, true, 22);
  for (Scene* s : {&off, &on}) {
    s->spheres.push_back({"ball", dvec3(20.0, 0.0, 0.0), 2.0f, 0.0f, {MaterialKind::Diffuse, vec3(1.0f)}});
    s->light.position = dvec3(20.0, 2.0, 0.0);
  }
  expect_same_expectation(render(off), render(on), "light on a ball");
}

// A light exactly on the inside of a closed sphere (radius R, albedo rho):
// half of its light enters, so at the first hit y, B = depth + 1,
//   L(y) = rho/pi [I cos/|c-y|^2 + (I/(2 R^2)) rho (1 - rho^(B-1))/(1 - rho)] / (4 pi).
// Without connections the bounces' variance is infinite (a bounce lands
// uniformly on the area, where the light's 1/(2 R d) at distance d from it
// has a divergent square integral); with them the pixels meet the closed form.
TEST(LightConnect, LightExactlyOnAClosedSphereKeepsTheClosedForm) {
  const double rho = 0.5, I = 1000.0, R = 10.0;
  const glm::dvec3 c(0.0, R, 0.0);
  const int size = 6, spp = 2048, depth = 2;
  Scene scene = closed_sphere(float(rho), vec3(c), depth, spp, size);
  scene.camera.position = vec3(0.0f, -5.0f, 0.0f);
  scene.camera.look_at = vec3(0.0f, -10.0f, 0.0f);
  scene.camera.up = vec3(0.0f, 0.0f, 1.0f);
  scene.settings.connect = true;
  scene.settings.split = {2, 2};
  expect_closed_form(render(scene), scene, ClosedSphereLight{rho, I, R, c, 0.5}, "light on the sphere");
}

// What it is for: at the 512 x 512 image's pixel size, on the cat, the
// variance of a typical pixel drops at equal samples (by a fifth, measured;
// by 40 % over the whole image, whose walls gain more).
TEST(LightConnect, LessNoiseOnTheCat) {
  const float zoom = 512.0f / 20.0f;
  const double ratio = expect_same_expectation(render(small("cat", 20, 64, false, 11, zoom)),
                                               render(small("cat", 20, 64, true, 22, zoom)), "cat zoomed");
  EXPECT_LT(ratio, 0.9);
}
