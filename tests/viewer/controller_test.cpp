// What the panel's requests do (viewer/controller.h): target raises, saving
// and loading scenes, dropped files, saved images, the held image.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <vector>

#include "geometry/mesh.h"
#include "render/progressive.h"
#include "scene/scene_io.h"
#include "viewer/controller.h"
#include "viewer/scene_diff.h"
#include "test_scenes.h"
#include "render_util.h"
#include "temp_dir.h"

using namespace whisker;

TEST(TargetRaise, OnlyARaiseCarriesOn) {
  Scene a = three_balls();
  a.settings.target_spp = 16;
  Scene b = a;
  b.settings.target_spp = 48;
  EXPECT_TRUE(only_target_raised(a, b));
  b.settings.target_spp = 0;  // never stop
  EXPECT_TRUE(only_target_raised(a, b));
  b.settings.target_spp = 8;  // lowered: restart for exactly 8
  EXPECT_FALSE(only_target_raised(a, b));
  b.settings.target_spp = 48;
  b.settings.fresnel = !a.settings.fresnel;  // with another edit: restart
  EXPECT_FALSE(only_target_raised(a, b));
  a.settings.target_spp = 0;  // from "never stop" to a number: restart
  b = a;
  b.settings.target_spp = 64;
  EXPECT_FALSE(only_target_raised(a, b));
}

// Save scene writes a file that loads back as the same scene, and never
// overwrites the previous one.
TEST(SaveScene, WritesALoadableSceneUnderAFreeName) {
  namespace fs = std::filesystem;
  const TempDir temp("save-scene");
  const fs::path& dir = temp.path();
  ProgressiveRenderer r(1);
  ViewerState s;
  s.initial = s.applied = s.edited = load_scene(resolve_scene("three-balls"));
  s.scene_label = "three-balls";
  s.save_dir = dir.string();
  Controller ctl{r, s};
  s.edited.light.position = vec3(1.0f, 2.0f, 3.0f);
  s.edited.settings.fresnel = true;
  ctl.apply_edits(0.0);
  ctl.save_scene();
  ctl.save_scene();
  EXPECT_FALSE(s.message_is_error) << s.message;
  ASSERT_TRUE(fs::exists(dir / "three-balls-edited.json"));
  ASSERT_TRUE(fs::exists(dir / "three-balls-edited-2.json"));
  const Scene back = load_scene(dir / "three-balls-edited.json");
  EXPECT_EQ(classify_change(s.applied, back), SceneChange::None);
}

// With edits that could be undone, a load waits for "discard the edits?";
// confirmed, it loads and clears the history.
TEST(LoadScene, AsksBeforeDiscardingEdits) {
  ProgressiveRenderer r(1);
  ViewerState s;
  s.initial = s.applied = s.edited = load_scene(resolve_scene("three-balls"));
  Controller ctl{r, s};
  ctl.load("diffuse-ball", 0.0);  // no edits yet: loads at once
  EXPECT_EQ(s.scene_label, "diffuse-ball");
  s.edited.light.intensity *= 2.0f;
  ctl.apply_edits(0.0);
  ctl.load("three-balls", 0.0);
  EXPECT_EQ(s.scene_label, "diffuse-ball");  // not yet
  EXPECT_EQ(s.pending_load, "three-balls");
  PanelRequests req;
  req.confirm_load = true;
  ctl.carry_out(req, 0.0);
  EXPECT_EQ(s.scene_label, "three-balls");
  EXPECT_TRUE(s.pending_load.empty());
  EXPECT_FALSE(s.history.can_undo());
}

// A scene file that does not load says so at once, without asking to
// discard the edits (which stay, undoable).
TEST(LoadScene, AFileThatDoesNotLoadAsksNothing) {
  ProgressiveRenderer r(1);
  ViewerState s;
  s.initial = s.applied = s.edited = load_scene(resolve_scene("three-balls"));
  s.scene_label = "three-balls";
  Controller ctl{r, s};
  s.edited.light.intensity *= 2.0f;
  ctl.apply_edits(0.0);
  ctl.load("/nonexistent/folder/scene.json", 0.0);
  EXPECT_TRUE(s.pending_load.empty());
  EXPECT_TRUE(s.message_is_error);
  EXPECT_NE(s.message.find("/nonexistent/folder/scene.json"), std::string::npos) << s.message;
  EXPECT_EQ(s.scene_label, "three-balls");
  EXPECT_TRUE(s.history.can_undo());
}

// A dropped scene file loads; a dropped OBJ goes into the current scene in
// place of its meshes; anything else is refused with a message naming it.
TEST(DropFile, SceneFilesLoadObjsReplaceMeshesOthersAreRefused) {
  PanelRequests req;
  std::string error;
  request_for_drop("/tmp/a/My Scene.JSON", req, error);
  EXPECT_EQ(req.load_scene, "/tmp/a/My Scene.JSON");
  EXPECT_TRUE(error.empty());
  PanelRequests obj;
  request_for_drop("/tmp/bunny.obj", obj, error);
  EXPECT_EQ(obj.load_mesh, "/tmp/bunny.obj");
  EXPECT_TRUE(obj.load_scene.empty());
  PanelRequests png;
  request_for_drop("/tmp/x.png", png, error);
  EXPECT_TRUE(png.load_scene.empty() && png.load_mesh.empty());
  EXPECT_NE(error.find("/tmp/x.png"), std::string::npos);

  // The OBJ replaces the cat scene's mesh: the triangle count follows it.
  namespace fs = std::filesystem;
  const TempDir temp("drop");
  const fs::path objp = temp.path() / "drop.obj";
  {
    std::ofstream out(objp);
    out << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n";
  }
  ProgressiveRenderer r(1);
  ViewerState s;
  s.scene_path = resolve_scene("cat").string();
  Controller ctl{r, s};
  PanelRequests drop;
  drop.load_mesh = objp.string();
  ctl.carry_out(drop, 0.0);
  EXPECT_FALSE(s.message_is_error) << s.message;
  ASSERT_EQ(s.applied.meshes.size(), 1u);
  EXPECT_EQ(s.applied.meshes[0].mesh->triangles.size(), 2u);
}

// Save: the float file beside the PNG records the render in its header
// (EXR) and is in display units (1.0 = the report's white) when asked.
TEST(SaveImage, FloatFileRecordsTheRenderAndCanBeDisplayReferred) {
  namespace fs = std::filesystem;
  const TempDir temp("save-image");
  const fs::path& dir = temp.path();
  Scene scene = sized("three-balls", 24, 16, 2, 2);
  scene.settings.seed = 9;
  ProgressiveRenderer r(1);
  ViewerState s;
  s.initial = s.applied = s.edited = scene;
  s.scene_label = "three-balls";
  s.save_dir = dir.string();
  s.snap = render(scene, 1);
  Controller ctl{r, s};
  ctl.save();
  EXPECT_FALSE(s.message_is_error) << s.message;
  s.save_display_units = true;
  ctl.save();
  EXPECT_FALSE(s.message_is_error) << s.message;
  EXPECT_NE(s.message.find("three-balls-2spp was taken"), std::string::npos) << s.message;
  const ImageAttributes a = render_record(scene, s.snap, true);
  const auto value = [&](const std::string& key) {
    for (const auto& [k, v] : a)
      if (k == key) return v;
    return std::string("(none)");
  };
  EXPECT_EQ(value("whisker.spp"), "2");
  EXPECT_EQ(value("whisker.seed"), "9");
  EXPECT_NE(value("whisker.settings").find("\"target_spp\":2"), std::string::npos);
  EXPECT_NE(value("whisker.camera").find("\"width\":24"), std::string::npos);
  EXPECT_NE(value("whisker.units").find("display"), std::string::npos);
  EXPECT_NE(value("whisker.seconds"), "(none)");
  if (have_exr()) {
    std::ifstream in(dir / "three-balls-2spp-2.exr", std::ios::binary);
    const std::string exr((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* text : {"whisker.spp", "whisker.seed", "whisker.seconds", "whisker.camera",
                             "whisker.settings", "display: 1.0 = 255^2.2"})
      EXPECT_NE(exr.find(text), std::string::npos) << text;
  } else {
    const Image radiance = read_pfm((dir / "three-balls-2spp.pfm").string());
    const Image display = read_pfm((dir / "three-balls-2spp-2.pfm").string());
    ASSERT_EQ(radiance.rgb.size(), display.rgb.size());
    for (std::size_t k = 0; k < radiance.rgb.size(); ++k)
      EXPECT_NEAR(display.rgb[k], radiance.rgb[k] / report_white(), 1e-5f * (1 + display.rgb[k]));
  }
}

// A/B: "Hold this image" keeps the image and its settings and turns the
// wipe on; an edit restarts the live render and leaves the held one alone.
TEST(Compare, HoldKeepsTheImageThroughAnEdit) {
  Scene scene = sized("three-balls", 16, 16, 1, 2);
  ProgressiveRenderer r(1);
  ViewerState s;
  s.initial = s.applied = s.edited = scene;
  Controller ctl{r, s};
  ctl.hold();  // nothing rendered yet
  EXPECT_TRUE(s.message_is_error);
  EXPECT_EQ(s.held.spp, 0u);
  s.snap = render(scene, 1);
  ctl.hold();
  EXPECT_FALSE(s.message_is_error) << s.message;
  EXPECT_EQ(s.held.spp, 2u);
  EXPECT_EQ(s.compare, kCompareWipe);
  EXPECT_NE(s.held_note.find("Fresnel off"), std::string::npos) << s.held_note;
  const std::vector<double> held = s.held.sum;
  s.edited.settings.fresnel = true;  // the three balls have glass: a restart
  const std::uint64_t before = s.generation;
  ctl.apply_edits(0.0);
  EXPECT_NE(s.generation, before);
  EXPECT_EQ(s.held.sum, held);
}

// A/B with the denoised view: "wipe: raw left, denoised right" shows (and
// saves) the live raw image's columns left of the line and its denoised
// copy's right of it; without the denoised view there is nothing to wipe.
TEST(Compare, RawLeftDenoisedRight) {
  ViewerState s;
  s.applied = sized("three-balls", 8, 2, 1, 2);
  Snapshot raw;
  raw.width = 8;
  raw.height = 2;
  raw.spp = 2;
  raw.generation = 1;
  raw.sum.assign(8 * 2 * 3, 2.0);  // mean 1
  raw.sum_sq.assign(8 * 2, 0.0);
  s.snap = raw;
  s.shown.image = raw;
  s.shown.own_spp = 2;
  s.denoised = raw;
  s.denoised.sum.assign(8 * 2 * 3, 6.0);  // mean 3
  s.compare = kCompareRawDenoised;
  s.wipe = 0.25f;  // two of the eight columns
  EXPECT_EQ(wipe_left(s), nullptr) << "the denoised view is off";
  s.denoised_view = true;
  ASSERT_EQ(wipe_left(s), &s.shown.image);
  const Snapshot m = shown_means(s);
  ASSERT_EQ(m.sum.size(), raw.sum.size());
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_FLOAT_EQ(float(m.sum[(std::size_t(y) * 8 + x) * 3]), x < 2 ? 1.0f : 3.0f) << x << "," << y;
}
