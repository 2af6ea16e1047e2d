// Scene files: the bundled scenes hold the report's numbers; bad files give
// one message naming the file and the field.
#include <gtest/gtest.h>

#include <filesystem>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "geometry/mesh.h"
#include "scene/scene_io.h"
#include "scene_refusal.h"
#include "temp_dir.h"

using namespace whisker;

namespace {

const char* kBall = R"({"spheres": [{"center": [0,0,0], "radius": 10, "material": {"type": "diffuse"}}]})";

}  // namespace

TEST(SceneFiles, BundledScenesHoldTheReportsNumbers) {
  for (const char* name : {"diffuse-ball", "three-balls", "three-balls-fresnel", "indirect",
                           "antialiased-ball"}) {
    const Scene s = load_scene(resolve_scene(name));
    EXPECT_EQ(s.name, name);
    EXPECT_EQ(s.camera.position, glm::dvec3(0, 0, 55));
    EXPECT_EQ(s.camera.width, 512);
    EXPECT_EQ(s.camera.height, 512);
    EXPECT_EQ(s.camera.fov_deg, 60.0f);
    EXPECT_EQ(s.light.position, glm::dvec3(-10, 20, 40));
    EXPECT_EQ(s.light.intensity, 2e10f);
    EXPECT_EQ(s.settings.max_depth, 5);
    // The room: six walls as docs/SCENES.md lists them.
    ASSERT_GE(s.spheres.size(), 7u);
    EXPECT_EQ(s.spheres[0].center, glm::dvec3(0, 1000, 0));
    EXPECT_EQ(s.spheres[0].radius, 940.0f);
    EXPECT_EQ(s.spheres[0].material.albedo, vec3(1, 0, 0));
    EXPECT_EQ(s.spheres[1].radius, 990.0f);
    EXPECT_EQ(s.spheres[1].material.albedo, vec3(0, 0, 1));
    EXPECT_EQ(s.spheres[2].center, glm::dvec3(0, 0, -1000));
    EXPECT_EQ(s.spheres[2].material.albedo, vec3(0, 1, 0));
    EXPECT_EQ(s.spheres[3].material.albedo, vec3(1, 0, 1));
    EXPECT_EQ(s.spheres[4].material.albedo, vec3(0, 1, 1));
    EXPECT_EQ(s.spheres[5].material.albedo, vec3(1, 1, 0));
  }
  const Scene f = load_scene(resolve_scene("three-balls-fresnel"));
  EXPECT_TRUE(f.settings.fresnel);
  EXPECT_EQ(f.settings.target_spp, 1024);
  EXPECT_EQ(f.spheres[6].material.kind, MaterialKind::Mirror);
  EXPECT_EQ(f.spheres[6].center, glm::dvec3(-20, 0, 0));
  EXPECT_EQ(f.spheres[7].material.kind, MaterialKind::Glass);
  EXPECT_EQ(f.spheres[7].material.ior, 1.5f);
  EXPECT_EQ(f.spheres[8].material.kind, MaterialKind::HollowGlass);
  EXPECT_EQ(f.spheres[8].radius, 10.0f);
  EXPECT_EQ(f.spheres[8].inner_radius, 9.8f);
  const Scene ind = load_scene(resolve_scene("indirect"));
  EXPECT_TRUE(ind.settings.indirect);
  EXPECT_EQ(ind.settings.target_spp, 32);
  const Scene aa = load_scene(resolve_scene("antialiased-ball"));
  EXPECT_TRUE(aa.settings.aa);
}

TEST(SceneFiles, RoundTripThroughJson) {
  Scene a = load_scene(resolve_scene("three-balls-fresnel"));
  a.settings.split_weights = vec3(1.0f, 0.5f, 0.25f);
  const Scene b = parse_scene(scene_to_json(a), "roundtrip.json");
  ASSERT_EQ(a.spheres.size(), b.spheres.size());
  for (std::size_t k = 0; k < a.spheres.size(); ++k) {
    EXPECT_EQ(a.spheres[k].center, b.spheres[k].center);
    EXPECT_EQ(a.spheres[k].radius, b.spheres[k].radius);
    EXPECT_EQ(a.spheres[k].material.kind, b.spheres[k].material.kind);
  }
  EXPECT_EQ(a.settings.fresnel, b.settings.fresnel);
  EXPECT_EQ(a.settings.split_weights, b.settings.split_weights);
  EXPECT_EQ(a.light.position, b.light.position);
}

// Saved scenes write each float by its shortest round-trip digits: the cat's
// mesh scale is "0.6", not 0.6000000238418579, and reads back the same.
TEST(SceneFiles, FloatsAreWrittenByTheirShortestDigits) {
  Scene a = load_scene(resolve_scene("cat"));
  a.spheres[0].radius = 9.8f;
  a.camera.fov_deg = 37.3f;
  const std::string text = scene_to_json(a);
  EXPECT_NE(text.find("\"scale\": 0.6,"), std::string::npos) << text;
  EXPECT_NE(text.find("9.8"), std::string::npos);
  EXPECT_NE(text.find("37.3"), std::string::npos);
  EXPECT_EQ(text.find("0000002"), std::string::npos) << text;  // 0.6000000238...
  EXPECT_EQ(text.find("99999"), std::string::npos) << text;    // 9.8 as 9.80000019 or 9.7999...
  const Scene b = parse_scene(text, "x.json", std::filesystem::path(a.source_path).parent_path());
  EXPECT_EQ(b.meshes[0].scale, a.meshes[0].scale);
  EXPECT_EQ(b.spheres[0].radius, 9.8f);
  EXPECT_EQ(b.camera.fov_deg, 37.3f);
}

TEST(SceneFiles, SyntaxErrorNamesLineAndColumn) {
  const std::string e = scene_refusal("{\n  \"name\": \"x\",\n  \"light\": {\"position\": [1, 2,, 3]}\n}");
  EXPECT_NE(e.find("bad.json:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("invalid JSON"), std::string::npos) << e;
}

TEST(SceneFiles, TheReadingPassRefusesKeysGivenTwiceAndDeepNesting) {
  // A key given twice deep inside is named by its path, arrays indexed.
  EXPECT_EQ(scene_refusal(R"({"description": [0, {"x": [[{"k": 1}, {"k": 2, "deep": {"a": 1,
                      "b": [], "a": 2}}]]}]})"),
            "bad.json: description[1].x[0][1].deep.a: given twice; keep one");
  // The same key in sibling objects is no duplicate; the document is built.
  EXPECT_EQ(scene_refusal(R"({"description": [{"k": 1}, {"k": 2}], "name": "n"})"), "(accepted)");
  // A syntax error after a key given twice is the file's first fault.
  const std::string syntax = scene_refusal("{\"name\": \"a\",\n \"name\": \"b\",}");
  EXPECT_EQ(syntax.rfind("bad.json:2:", 0), 0u) << syntax;
  EXPECT_NE(syntax.find("invalid JSON"), std::string::npos) << syntax;
  // Nesting: 64 levels are read, the 65th is refused where it opens.
  EXPECT_EQ(scene_refusal("{\"description\":\n" + std::string(63, '[') + std::string(63, ']') + "}"),
            "(accepted)");
  EXPECT_EQ(scene_refusal("{\"description\":\n" + std::string(64, '[') + std::string(64, ']') + "}"),
            "bad.json:2:64: arrays and objects nested deeper than 64 levels");
}

TEST(SceneFiles, BadFieldsAreNamed) {
  struct Case { const char* text; const char* expect; };
  const Case cases[] = {
      {R"({"lights": {}})", "bad.json: lights: unknown key"},
      {R"({"light": {"position": [1, 2]}})", "bad.json: light.position: must be an array of 3 numbers"},
      {R"({"light": {"position": [1, "2", 3]}})", "bad.json: light.position[1]: must be a number"},
      {R"({"light": {"intensity": -5}})", "bad.json: light.intensity: must be in [0"},
      {R"({"light": {"intensity": 1e999}})", "bad.json: invalid JSON: number overflow parsing '1e999'"},
      {R"({"camera": {"up": [0, 0, 0]}})", "bad.json: camera.up: must not be zero-length"},
      {R"({"camera": {"width": 0}})", "bad.json: camera.width: must be in [1, 16384]"},
      {R"({"camera": {"width": 16385}})", "bad.json: camera.width: must be in [1, 16384], got 16385"},
      {R"({"camera": {"width": 1.5}})", "bad.json: camera.width: must be an integer"},
      {R"({"camera": {"look_at": [0, 0, 55]}})", "bad.json: camera.look_at: must differ"},
      {R"({"settings": {"indirect": "yes"}})", "bad.json: settings.indirect: must be true or false"},
      {R"({"settings": {"max_depth": -1}})", "bad.json: settings.max_depth: must be in [0, 1000]"},
      {R"({"settings": {"accel": "kd"}})", "bad.json: settings.accel: unknown accel"},
      {R"({"settings": {"split": 0}})", "bad.json: settings.split: factors must be in [1, 64], got 0"},
      {R"({"settings": {"split": [4, "4"]}})", "bad.json: settings.split[1]: must be an integer"},
      {R"({"settings": {"split": [64, 64, 2]}})", "bad.json: settings.split: the factors' product"},
      {R"({"settings": {"split": 4.5}})", "bad.json: settings.split: must be an integer or an array"},
      {R"({"settings": {"split_weights": [1, 0, 1]}})", "bad.json: settings.split_weights[1]: must be in [0.01, 1]"},
      {R"({"settings": {"split_weights": [1, 1]}})", "bad.json: settings.split_weights: must be an array of 3 numbers"},
      {R"({"settings": {"split_weights": [1, 1, 2]}})", "bad.json: settings.split_weights[2]: must be in [0.01, 1]"},
      {R"({"spheres": {}})", "bad.json: spheres: must be an array"},
      {R"({"spheres": [{"center": [0,0,0], "radius": -1, "material": {"type": "diffuse"}}]})",
       "bad.json: spheres[0].radius: must be positive"},
      {R"({"spheres": [{"center": [0,0,0], "material": {"type": "diffuse"}}]})",
       "bad.json: spheres[0].radius: missing"},
      {R"({"spheres": [{"center": [0,0,0], "radius": 1, "material": {"type": "gold"}}]})",
       "bad.json: spheres[0].material.type: unknown material \"gold\""},
      {R"({"spheres": [{"center": [0,0,0], "radius": 1, "material": {"type": "diffuse", "albedo": [2, 0, 0]}}]})",
       "bad.json: spheres[0].material.albedo[0]: must be in [0, 1]"},
      {R"({"spheres": [{"center": [0,0,0], "radius": 1, "material": {"type": "mirror", "ior": 1.5}}]})",
       "bad.json: spheres[0].material.ior: only glass"},
      {R"({"spheres": [{"center": [0,0,0], "radius": 10, "material": {"type": "hollow_glass"}}]})",
       "bad.json: spheres[0].inner_radius: missing"},
      {R"({"spheres": [{"center": [0,0,0], "radius": 10, "inner_radius": 12, "material": {"type": "hollow_glass"}}]})",
       "bad.json: spheres[0].inner_radius: must be smaller than radius"},
      {R"({"meshes": [{"path": "no-such-mesh.obj"}]})", "bad.json: meshes[0].path: mesh \"no-such-mesh.obj\" not found"},
      {R"([1, 2])", "bad.json: top level: must be an object"},
  };
  for (const Case& c : cases) {
    const std::string e = scene_refusal(c.text);
    EXPECT_NE(e.find(c.expect), std::string::npos) << "input: " << c.text << "\nmessage: " << e;
  }
  EXPECT_EQ(scene_refusal(kBall), "(accepted)");
}

TEST(SceneFiles, MissingFileNamesTheBundledScenes) {
  try {
    load_scene(resolve_scene("no-such-scene"));
    FAIL() << "expected an error";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("no-such-scene.json: scene file not found"), std::string::npos) << m;
    EXPECT_NE(m.find("three-balls"), std::string::npos) << m;
  }
}

TEST(SceneFiles, PositionsKeepTheDigitsTheFileWrote) {
  // 1000.0001 is not a float (the nearest is 1000.00012207...): the reader
  // keeps positions in double, and writing them back loses nothing.
  const Scene s = parse_scene(R"({"camera": {"position": [1000.0001, -999.9999, 123456.789], "look_at": [1000, -1000, 123456]},
    "light": {"position": [1000.00005, 0, 0]},
    "spheres": [{"center": [1000.0000001, 0, 0], "radius": 1e-4, "material": {"type": "diffuse"}}]})",
                              "digits.json");
  EXPECT_EQ(s.camera.position, glm::dvec3(1000.0001, -999.9999, 123456.789));
  EXPECT_EQ(s.light.position.x, 1000.00005);
  EXPECT_EQ(s.spheres[0].center.x, 1000.0000001);
  const Scene back = parse_scene(scene_to_json(s), "roundtrip.json");
  EXPECT_EQ(back.camera.position, s.camera.position);
  EXPECT_EQ(back.camera.look_at, s.camera.look_at);
  EXPECT_EQ(back.light.position, s.light.position);
  EXPECT_EQ(back.spheres[0].center, s.spheres[0].center);
}

// The viewer's Save scene writes into another folder than the scene's: the
// mesh paths must lead from there to the OBJs loaded ("kitty.obj" beside the
// original scene was written as "kitty.obj" and did not load).
TEST(SceneFiles, SavedSceneFindsItsMeshesFromAnotherFolder) {
  namespace fs = std::filesystem;
  const TempDir temp("save");
  const fs::path& root = temp.path();
  fs::create_directories(root / "orig");
  fs::create_directories(root / "saved" / "deeper");
  fs::copy_file(resolve_mesh("cat.obj", {}, "cat"), root / "orig" / "kitty.obj");
  std::ifstream in(resolve_scene("cat"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find("\"cat.obj\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 9, "\"kitty.obj\"");
  std::ofstream(root / "orig" / "cat.json") << text;
  const Scene cat = load_scene(root / "orig" / "cat.json");
  ASSERT_EQ(cat.meshes.size(), 1u);

  for (const fs::path& out : {root / "saved" / "deeper" / "cat.json", root / "cat.json"}) {
    std::ofstream(out) << scene_to_json(cat, out);
    Scene back;
    ASSERT_NO_THROW(back = load_scene(out)) << out;
    ASSERT_EQ(back.meshes.size(), 1u);
    EXPECT_EQ(fs::path(back.meshes[0].path).is_relative(), true) << back.meshes[0].path;
    EXPECT_EQ(fs::canonical(back.meshes[0].file), fs::canonical(root / "orig" / "kitty.obj"));
    EXPECT_EQ(back.meshes[0].mesh->positions, cat.meshes[0].mesh->positions);
  }
}

// A mesh file named several times is one mesh in memory, its positions
// those of its first mention (it was 8 copies of the cat for a scene naming
// it 8 times, then one for each distinct placement); the World places the
// others as instances of it (tests/instances_test.cpp).
TEST(SceneFiles, AMeshNamedManyTimesIsLoadedOnce) {
  std::string meshes;
  for (int i = 0; i < 8; ++i)
    meshes += std::string(i ? ", " : "") + R"({"path": "cat.obj", "translate": [)" +
              (i < 6 ? "0" : std::to_string(i)) + ", 0, 0]}";
  const Scene s = parse_scene(R"({"meshes": [)" + meshes + "]}", "many.json");
  ASSERT_EQ(s.meshes.size(), 8u);
  for (int i = 1; i < 8; ++i) EXPECT_EQ(s.meshes[i].mesh.get(), s.meshes[0].mesh.get()) << i;
  ASSERT_TRUE(s.meshes[0].mesh->placed.has_value());
  EXPECT_EQ(s.meshes[0].mesh->placed->translate, dvec3(0.0));
  EXPECT_EQ(s.meshes[7].translate, dvec3(7.0, 0.0, 0.0));
  EXPECT_EQ(s.meshes[7].mesh->exact[0].x, s.meshes[0].mesh->exact[0].x);
}
