// A mesh file placed several times: held once (its triangles and BVH), each
// placement an instance of it (scene/world.h), with the hits, records and
// shadows of the same placements each loaded on its own.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>

#include <fcntl.h>
#include <glm/geometric.hpp>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include "geometry/mesh.h"
#include "scene/mesh_io.h"
#include "scene/scene_io.h"
#include "scene/world.h"
#include "directions.h"
#include "sanitized.h"
#include "temp_dir.h"

extern char** environ;

using namespace whisker;
namespace fs = std::filesystem;

namespace {

// The cat three times: as the cat scene places it, smaller and moved, and
// far off at a twentieth of its size; each its own colour.
const char* kThreeCats = R"({
  "camera": {"position": [0, 0, 55]},
  "meshes": [
    {"path": "cat.obj", "scale": 0.6, "translate": [0, -10, 0],
     "material": {"type": "diffuse", "albedo": [1, 0, 0]}},
    {"path": "cat.obj", "scale": 0.25, "translate": [-20, 5, 10],
     "material": {"type": "diffuse", "albedo": [0, 1, 0]}},
    {"path": "cat.obj", "scale": 0.05, "translate": [300, 40, -200],
     "material": {"type": "diffuse", "albedo": [0, 0, 1]}}]})";

// The same scene with each placement loaded on its own (as every mention
// was before meshes were shared): three meshes, each placed once.
Scene each_loaded_alone(const Scene& shared) {
  Scene alone = shared;
  for (MeshObject& m : alone.meshes)
    m.mesh = std::make_shared<const TriangleMesh>(load_obj(m.file, m.scale, m.translate));
  return alone;
}

// A random ray from around the camera towards the three cats.
Ray towards_the_cats(std::mt19937& g, const World& world, int k) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  static const glm::dvec3 targets[] = {{0, 0, 0}, {-20, 8, 10}, {300, 41, -200}};
  static const double spread[] = {14.0, 6.0, 1.2};
  const glm::dvec3 aim = targets[k % 3] + spread[k % 3] * glm::dvec3(u(g), 0.7 * u(g), 0.5 * u(g));
  const glm::dvec3 from(8.0 * u(g), 8.0 * u(g), 55.0 + 8.0 * u(g));
  return world.to_render(from, vec3(glm::normalize(aim - from)));
}

}  // namespace

TEST(Instances, AFileNamedManyTimesIsHeldOnce) {
  // Eight placements of the cat (it was 8 copies of its triangles, and 8 in
  // the BVH): one mesh, one stored copy of its triangles; a ray sees eight.
  std::string meshes;
  for (int i = 0; i < 8; ++i)
    meshes += std::string(i ? ", " : "") + R"({"path": "cat.obj", "scale": )" +
              std::to_string(0.1 + 0.05 * i) + R"(, "translate": [)" + std::to_string(10 * i) + ", 0, 0]}";
  const Scene s = parse_scene(R"({"meshes": [)" + meshes + "]}", "many.json");
  ASSERT_EQ(s.meshes.size(), 8u);
  for (int i = 1; i < 8; ++i) EXPECT_EQ(s.meshes[i].mesh.get(), s.meshes[0].mesh.get()) << i;
  ASSERT_TRUE(s.meshes[0].mesh->placed.has_value());
  EXPECT_EQ(s.meshes[0].mesh->placed->scale, 0.1f);
  const World world(s);
  const std::size_t once = s.meshes[0].mesh->triangles.size();
  EXPECT_EQ(world.stored_triangle_count(), once);
  EXPECT_EQ(world.triangle_count(), 8 * once);
  EXPECT_EQ(world.instance_count(), 8u);
}

TEST(Instances, APlacementTakingAVertexPastFloatIsRefused) {
  // What loading each placement on its own checked: the second placement
  // (1e32 scaled by 1e7) is past float; the first is not.
  const TempDir temp("far");
  const fs::path& dir = temp.path();
  std::ofstream(dir / "far.obj") << "v 0 0 0\nv 1e32 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string text = R"({"meshes": [{"path": "far.obj"}, {"path": "far.obj", "scale": 1e7}]})";
  std::string what = "(accepted)";
  try {
    parse_scene(text, "far.json", dir);
  } catch (const SceneError& e) {
    what = e.what();
  }
  EXPECT_EQ(what, "far.json: meshes[1].path: " + (dir / "far.obj").string() +
                      ": a vertex is not finite after scale/translate");
}

TEST(Instances, HitsAndShadowsAreThoseOfEachPlacementLoadedAlone) {
  const Scene shared = parse_scene(kThreeCats, "three.json");
  ASSERT_EQ(shared.meshes[2].mesh.get(), shared.meshes[0].mesh.get());
  const Scene alone = each_loaded_alone(shared);
  ASSERT_NE(alone.meshes[2].mesh.get(), alone.meshes[0].mesh.get());
  const World a(shared), b(alone);
  EXPECT_EQ(a.instance_count(), 3u);
  EXPECT_EQ(b.instance_count(), 0u);
  EXPECT_EQ(a.triangle_count(), b.triangle_count());
  std::mt19937 g(7);
  int hits[3] = {0, 0, 0}, disagree = 0, shadowed = 0;
  const int rays = release_or_sanitized(60000, 6000);
  for (int k = 0; k < rays; ++k) {
    const Ray r = towards_the_cats(g, a, k);
    SurfaceHit ha, hb;
    const bool fa = a.intersect(r, ha), fb = b.intersect(r, hb);
    // Both frames round the triangles differently: a ray grazing an edge
    // may pass on one side in one and the other in the other.
    if (fa != fb || (fa && ha.material->albedo != hb.material->albedo)) {
      ++disagree;
      continue;
    }
    if (!fa) continue;
    const int cat = ha.material->albedo.x > 0 ? 0 : ha.material->albedo.y > 0 ? 1 : 2;
    ++hits[cat];
    const float tol = 2e-5f * ha.t;
    ASSERT_NEAR(ha.t, hb.t, tol) << k;
    ASSERT_LT(glm::length(ha.p - hb.p), tol + 1e-5f) << k;
    // The far cat's triangles are 0.02 across at 350 from the camera: placed
    // alone in render space their float corners (ulp 3e-5) tilt them, a thin
    // sliver by tens of degrees, so there only the side they face is kept.
    ASSERT_GT(glm::dot(ha.ng, hb.ng), cat == 2 ? 0.0f : 0.99999f) << k;
    // Shadow segments short of the hit and past it.
    const Ray before{r.o, r.d, 0.0f, ha.t * (1.0f - 1e-4f)}, past{r.o, r.d, 0.0f, ha.t * (1.0f + 1e-4f)};
    ASSERT_EQ(a.occluded(before), b.occluded(before)) << k;
    ASSERT_TRUE(a.occluded(past)) << k;
    // The shadow ray to the light, by the test that skips the spheres
    // (there are none): the light buffer in one, the instances in the other.
    const vec3 light = a.light().position;
    const auto to_light = [&](const World& w, const SurfaceHit& h) {
      const vec3 from = h.p - light;
      return w.occluded_to_light(spawn_shadow_ray(h, light), glm::dot(from, from), from);
    };
    const bool sa = to_light(a, ha);
    shadowed += sa;
    disagree += sa != to_light(b, hb);
  }
  for (int cat = 0; cat < 3; ++cat) EXPECT_GT(hits[cat], rays / 10) << cat;
  EXPECT_GT(shadowed, rays / 50);  // enough shadow rays blocked to compare (about 4 %)
  EXPECT_LT(disagree, rays / 1000);
}

TEST(Instances, RaysLeavingAnInstanceNeverMeetItsTriangleAgain) {
  // From hit points on each instance (the far, small one too), rays leave
  // to the side of the surface they go to: none meets the triangle it left
  // (the point's bound covers the move into the instance's frame and back).
  const World world(parse_scene(kThreeCats, "three.json"));
  std::mt19937 g(11);
  int left = 0, again = 0;
  for (int k = 0; k < release_or_sanitized(60000, 6000); ++k) {
    const Ray r = towards_the_cats(g, world, k);
    Hit first;
    if (!world.closest(r, first) || first.instance == kNoSkip) continue;
    SurfaceHit h;
    world.record(r, first, h);
    for (int n = 0; n < 4; ++n) {
      const Ray out = spawn_ray(h, random_direction(g));
      Hit next;
      ++left;
      if (world.closest(out, next) && next.instance == first.instance && next.prim == first.prim) ++again;
    }
    // And the shadow ray to the light, from either side.
    const Ray shadow = spawn_shadow_ray(h, world.light().position);
    Hit blocker;
    if (world.closest(shadow, blocker) && blocker.instance == first.instance && blocker.prim == first.prim)
      ++again;
  }
  EXPECT_GT(left, 10000);
  EXPECT_EQ(again, 0);
}

namespace {

// The peak resident memory (kB) of `whisker ARGS...`, alone: wait4 reports
// the one child's.
long peak_kb(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  std::string bin = WHISKER_BIN;
  argv.push_back(bin.data());
  std::vector<std::string> copy = args;
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t quiet;
  posix_spawn_file_actions_init(&quiet);
  posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&quiet, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, bin.c_str(), &quiet, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&quiet);
  if (spawned != 0) return -1;
  int status = 0;
  struct rusage ru {};
  if (wait4(pid, &status, 0, &ru) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
  return ru.ru_maxrss;
}

}  // namespace

TEST(Instances, EightPlacementsCostAboutWhatOneDoes) {
  // The cat once, then at eight places, each a 16 x 16 render of one pass:
  // eight took 11 MB more than one (the cat's triangles, BVH and light
  // buffer, 8 times); now the placements share one copy.
  if (release_or_sanitized(0, 1)) GTEST_SKIP() << "a sanitizer's allocator keeps memory of its own";
  const TempDir temp("instances");
  const fs::path& dir = temp.path();
  const auto scene = [&](int n) {
    std::string meshes;
    for (int i = 0; i < n; ++i)
      meshes += std::string(i ? ", " : "") + R"({"path": ")" + std::string(WHISKER_ASSETS_DIR) +
                R"(/cat.obj", "scale": 0.2, "translate": [)" + std::to_string(-18 + 12 * (i % 4)) + ", " +
                std::to_string(-10 + 10 * (i / 4)) + ", 0]}";
    const fs::path p = dir / ("cats" + std::to_string(n) + ".json");
    std::ofstream(p) << R"({"camera": {"width": 16, "height": 16}, "meshes": [)" << meshes << "]}";
    return p.string();
  };
  const auto run = [&](int n) {
    return peak_kb({"--headless", "--scene", scene(n), "--frames", "1", "--spp", "1", "--threads", "1",
                    "--quiet", "--out", (dir / "out.png").string()});
  };
  const long one = run(1), eight = run(8);
  ASSERT_GT(one, 0);
  ASSERT_GT(eight, 0);
  EXPECT_LT(eight, one + 1024) << "one cat: " << one << " kB, eight: " << eight << " kB";
}
