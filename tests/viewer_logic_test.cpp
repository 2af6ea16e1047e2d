// The viewer's window-free logic: which edits restart the render, the mouse
// camera moves, and which keys and mouse states give which action.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>
#include <thread>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "geometry/mesh.h"
#include "render/progressive.h"
#include "scene/scene_io.h"
#include "scene/world.h"
#include "viewer/blend.h"
#include "viewer/camera_control.h"
#include "viewer/controller.h"
#include "viewer/debug_views.h"
#include "viewer/history.h"
#include "viewer/display.h"
#include "viewer/input.h"
#include "viewer/scene_diff.h"
#include "render_util.h"

using namespace whisker;

namespace {

Scene three_balls() {
  Scene s;
  SphereObject a;
  a.name = "mirror";
  a.center = {-20, 0, 0};
  a.radius = 10;
  a.material.kind = MaterialKind::Mirror;
  s.spheres.push_back(a);
  SphereObject b = a;
  b.name = "hollow";
  b.center = {20, 0, 0};
  b.inner_radius = 9.8f;
  b.material.kind = MaterialKind::HollowGlass;
  s.spheres.push_back(b);
  return s;
}

}  // namespace

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

TEST(CameraControl, OrbitKeepsDistanceAndTarget) {
  Camera c;
  const float r = glm::length(c.position - c.look_at);
  orbit(c, 0.7f, -0.3f);
  EXPECT_NEAR(glm::length(c.position - c.look_at), r, 1e-3f * r);
  EXPECT_EQ(c.look_at, glm::dvec3(0.0));
  EXPECT_GT(std::fabs(c.position.x), 1.0f);
  EXPECT_GT(c.position.y, 1.0f);  // dragging up-screen lifts the eye (dy < 0)
}

TEST(CameraControl, OrbitStopsBeforeThePole) {
  Camera c;
  orbit(c, 0.0f, -10.0f);  // far past straight above
  const vec3 dir = vec3(glm::normalize(c.position - c.look_at));
  EXPECT_LT(glm::dot(dir, vec3(0, 1, 0)), std::cos(glm::radians(0.5f)));
  EXPECT_GT(glm::dot(dir, vec3(0, 1, 0)), std::cos(glm::radians(1.5f)));
}

TEST(CameraControl, PanFollowsTheMouse) {
  Camera c;  // at (0,0,55) looking at the origin, 60 degrees over 512 px
  const glm::dvec3 view = c.look_at - c.position;
  pan(c, 10.0f, 0.0f);
  // Dragging right moves the eye left by 10 pixels' worth at the target.
  const float per_px = 2.0f * 55.0f * std::tan(glm::radians(30.0f)) / 512.0f;
  EXPECT_NEAR(c.position.x, -10.0f * per_px, 1e-4f);
  EXPECT_NEAR(c.look_at.x, -10.0f * per_px, 1e-4f);
  EXPECT_LT(glm::length(c.look_at - c.position - view), 1e-4f);
}

TEST(CameraControl, DollyScalesDistance) {
  Camera c;
  dolly(c, 0.5f);
  EXPECT_NEAR(c.position.z, 27.5f, 1e-4f);
  dolly(c, 0.0f);  // never onto the target itself
  EXPECT_GT(glm::length(c.position - c.look_at), 0.0f);
}

TEST(FitImage, OneToOneWhenItFits) {
  const PixelRect r = fit_image({0, 0, 600, 720}, 512, 512);
  EXPECT_EQ(r.w, 512);
  EXPECT_EQ(r.h, 512);
  EXPECT_EQ(r.x, 44);
  EXPECT_EQ(r.y, 104);
  const PixelRect z = fit_image({0, 0, 1100, 1100}, 512, 512);  // integer zoom
  EXPECT_EQ(z.w, 1024);
  const PixelRect s = fit_image({0, 0, 256, 400}, 512, 512);  // shrink, keep aspect
  EXPECT_EQ(s.w, 256);
  EXPECT_EQ(s.h, 256);
}

TEST(InputMapping, ShortcutKeysGiveTheirRequests) {
  KeyPresses keys;
  keys.space = keys.r = keys.s = keys.c = keys.escape = true;
  PanelRequests req;
  map_keys(keys, false, req);
  EXPECT_TRUE(req.toggle_pause);
  EXPECT_TRUE(req.restart);
  EXPECT_TRUE(req.save);
  EXPECT_TRUE(req.print_camera);
  EXPECT_TRUE(req.quit);

  PanelRequests only_r;
  KeyPresses r;
  r.r = true;
  map_keys(r, false, only_r);
  EXPECT_TRUE(only_r.restart);
  EXPECT_FALSE(only_r.toggle_pause || only_r.save || only_r.print_camera || only_r.quit);
}

TEST(InputMapping, KeysAreIgnoredWhileImGuiTakesText) {
  KeyPresses keys;
  keys.space = keys.r = keys.s = keys.c = keys.escape = true;
  PanelRequests req;
  map_keys(keys, true, req);  // e.g. typing "s" into the path field
  EXPECT_FALSE(req.toggle_pause || req.restart || req.save || req.print_camera || req.quit);
  // A request the panel already made is kept.
  req.save = true;
  map_keys(keys, true, req);
  EXPECT_TRUE(req.save);
}

TEST(InputMapping, LeftDragOnTheImageOrbits) {
  Camera c;
  MouseCamera mouse;
  MouseInput in;
  in.clicked[0] = in.down[0] = true;
  mouse.update(c, in, 1.0f);  // press on the image: no move yet
  EXPECT_EQ(c.position, Camera().position);
  in.clicked[0] = false;
  in.dx = 50.0f;
  mouse.update(c, in, 1.0f);
  EXPECT_NE(c.position.x, 0.0f);
  EXPECT_EQ(c.look_at, glm::dvec3(0.0));  // orbit keeps the target
  // After the release the same motion does nothing.
  const glm::dvec3 after = c.position;
  in.down[0] = false;
  mouse.update(c, in, 1.0f);
  EXPECT_EQ(c.position, after);
}

TEST(InputMapping, DragStartedOnThePanelNeverMovesTheCamera) {
  Camera c;
  MouseCamera mouse;
  MouseInput in;
  in.clicked[0] = in.down[0] = true;
  in.imgui_wants_mouse = true;  // pressed over the panel
  mouse.update(c, in, 1.0f);
  in.clicked[0] = false;
  in.imgui_wants_mouse = false;  // dragged out over the image
  in.dx = -80.0f;
  in.dy = 30.0f;
  mouse.update(c, in, 1.0f);
  EXPECT_EQ(c.position, Camera().position);
  // The wheel over the panel scrolls it, not the camera.
  in.down[0] = false;
  in.dx = in.dy = 0.0f;
  in.wheel = 2.0f;
  in.imgui_wants_mouse = true;
  mouse.update(c, in, 1.0f);
  EXPECT_EQ(c.position, Camera().position);
}

TEST(InputMapping, RightDragPansAndWheelDollies) {
  Camera c;
  MouseCamera mouse;
  MouseInput in;
  in.clicked[1] = in.down[1] = true;
  mouse.update(c, in, 1.0f);
  in.clicked[1] = false;
  in.dx = 10.0f;
  mouse.update(c, in, 2.0f);  // 2 image pixels per window unit: 5 pixels
  Camera expected;
  pan(expected, 5.0f, 0.0f);
  EXPECT_NEAR(c.position.x, expected.position.x, 1e-5f);
  EXPECT_NEAR(c.look_at.x, expected.look_at.x, 1e-5f);

  Camera d;
  MouseInput wheel;
  wheel.wheel = 1.0f;
  MouseCamera().update(d, wheel, 1.0f);
  EXPECT_NEAR(d.position.z, 55.0f * 0.9f, 1e-4f);
}

TEST(TargetSpp, OnlyARaiseCarriesOn) {
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

// Raising the target after it was reached renders more passes in the same
// generation, and the result is the same image as a render to the higher
// target from the start (samples are indexed, so nothing repeats).
TEST(TargetSpp, RaisingTheTargetContinuesTheAccumulation) {
  Scene s = load_scene(resolve_scene("three-balls"));
  s.camera.width = 40;
  s.camera.height = 32;
  s.settings.indirect = s.settings.aa = true;
  s.settings.spp = 2;
  s.settings.target_spp = 4;

  ProgressiveRenderer r(2);
  const std::uint64_t gen = r.set_scene(s);
  r.start();
  ASSERT_TRUE(r.wait_for(gen, 4));
  Snapshot first;
  r.snapshot(first);
  EXPECT_TRUE(first.done);
  r.set_target_spp(10);
  ASSERT_TRUE(r.wait_for(gen, 10));
  Snapshot more;
  r.snapshot(more);
  r.stop();
  EXPECT_EQ(more.generation, gen);
  EXPECT_EQ(more.spp, 10u);
  EXPECT_EQ(more.counters.passes, 5u);  // 2 + 2 + 2 + 2 + 2: the first two were kept
  EXPECT_TRUE(more.done);

  s.settings.target_spp = 10;
  const Snapshot ref = render(s, 2);  // the same target from the start
  EXPECT_EQ(more.sum, ref.sum);
  EXPECT_EQ(more.sum_sq, ref.sum_sq);
}

// A pass reports its tiles as they finish; between passes nothing runs.
TEST(TargetSpp, PassProgressCountsTiles) {
  Scene s = load_scene(resolve_scene("three-balls"));
  s.camera.width = 70;  // 3 x 2 tiles of 32
  s.camera.height = 40;
  s.settings.spp = 1;
  s.settings.target_spp = 2;
  ProgressiveRenderer r(1);
  const std::uint64_t gen = r.set_scene(s);
  r.start();
  ASSERT_TRUE(r.wait_for(gen, 2));
  // Done: the workers wait, so the progress is "not rendering".
  for (int k = 0; k < 100 && r.pass_progress().rendering; ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const auto p = r.pass_progress();
  r.stop();
  EXPECT_FALSE(p.rendering);
  EXPECT_EQ(p.generation, gen);
  EXPECT_EQ(p.tiles_total, 6);
  EXPECT_EQ(p.tiles_done, 6);
}

TEST(EditHistory, ADragIsOneStepAndUndoRedoWalkIt) {
  EditHistory h;
  Scene a = three_balls(), b = a, c = a;
  b.light.position.x = 5.0f;
  c.light.position.x = 9.0f;
  h.changed(a);  // a drag: a -> b -> c, one gesture
  h.changed(b);
  h.settle();
  EXPECT_EQ(h.steps(), 1u);
  Scene cur = c;
  ASSERT_TRUE(h.undo(cur));
  EXPECT_EQ(cur.light.position.x, a.light.position.x);  // back before the drag
  EXPECT_FALSE(h.can_undo());
  ASSERT_TRUE(h.redo(cur));
  EXPECT_EQ(cur.light.position.x, 9.0f);
  EXPECT_FALSE(h.redo(cur));
  // A new edit after an undo drops the redo branch.
  ASSERT_TRUE(h.undo(cur));
  h.changed(cur);
  EXPECT_FALSE(h.can_redo());
}

TEST(InputMapping, CtrlZAndCtrlYUndoAndRedoButNotWhileTyping) {
  KeyPresses k;
  k.undo = true;
  PanelRequests req;
  map_keys(k, false, req);
  EXPECT_TRUE(req.undo);
  EXPECT_FALSE(req.redo);
  k.undo = false;
  k.redo = true;
  PanelRequests typing;
  map_keys(k, true, typing);  // a text field has its own undo
  EXPECT_FALSE(typing.redo);
}

// Save scene writes a file that loads back as the same scene, and never
// overwrites the previous one.
TEST(SaveScene, WritesALoadableSceneUnderAFreeName) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("whisker-save-scene-" + std::to_string(::getpid()));
  fs::remove_all(dir);
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
  fs::remove_all(dir);
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

// Debug views of the three balls: the centre ray meets the glass ball
// (centre 0, radius 10) head on, 45 units from the eye at z = 55; the
// bottom row sees the blue floor.
TEST(DebugViews, NormalsMaterialsAndDepthOfTheThreeBalls) {
  const Scene s = load_scene(resolve_scene("three-balls"));
  const int w = s.camera.width, h = s.camera.height;
  const auto px = [&](const DebugImage& d, int i, int j, int c) {
    return d.image.sum[(std::size_t(i) * w + j) * 3 + c];
  };
  const DebugImage n = render_debug_view(s, kViewNormals);
  EXPECT_NEAR(px(n, h / 2, w / 2, 0), 0.5f, 0.01f);
  EXPECT_NEAR(px(n, h / 2, w / 2, 1), 0.5f, 0.01f);
  EXPECT_NEAR(px(n, h / 2, w / 2, 2), 1.0f, 0.01f);  // facing the camera: +z
  EXPECT_NEAR(px(n, h - 1, w / 2, 1), 1.0f, 0.01f);  // the floor faces up: +y

  const DebugImage m = render_debug_view(s, kViewAlbedo);
  EXPECT_FLOAT_EQ(px(m, h / 2, w / 2, 0), kGlassColour.x);
  EXPECT_EQ(px(m, h - 1, w / 2, 0), 0.0f);  // floor albedo (0, 0, 1)
  EXPECT_EQ(px(m, h - 1, w / 2, 2), 1.0f);

  const DebugImage d = render_debug_view(s, kViewDepth);
  ASSERT_GT(d.far, 45.0f);
  EXPECT_NEAR((1.0f - px(d, h / 2, w / 2, 0)) * d.far, 45.0f, 0.05f);
  EXPECT_NE(debug_legend(d).find("depth"), std::string::npos);
}

// During a long pass the tiles done climb before the pass publishes.
TEST(TargetSpp, PassProgressClimbsDuringALongPass) {
  Scene s = load_scene(resolve_scene("three-balls"));
  s.camera.width = 64;  // 2 x 2 tiles
  s.camera.height = 64;
  s.settings.spp = 300;
  s.settings.target_spp = 300;
  ProgressiveRenderer r(1);
  const std::uint64_t gen = r.set_scene(s);
  r.start();
  bool seen_midway = false;
  for (int k = 0; k < 2000 && !seen_midway; ++k) {
    const auto p = r.pass_progress();
    Snapshot snap;
    const bool published = r.snapshot(snap) && snap.spp > 0;
    seen_midway = p.rendering && p.generation == gen && p.pass_spp == 300 &&
                  p.tiles_done > 0 && p.tiles_done < p.tiles_total && !published;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  r.stop();
  EXPECT_TRUE(seen_midway);
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
  const fs::path objp = fs::temp_directory_path() / ("whisker-drop-" + std::to_string(::getpid()) + ".obj");
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
  fs::remove(objp);
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

// Save: the float file beside the PNG records the render in its header
// (EXR) and is in display units (1.0 = the report's white) when asked.
TEST(SaveImage, FloatFileRecordsTheRenderAndCanBeDisplayReferred) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("whisker-save-image-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  Scene scene = load_scene(resolve_scene("three-balls"));
  scene.camera.width = 24;
  scene.camera.height = 16;
  scene.settings.spp = 2;
  scene.settings.target_spp = 2;
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
  fs::remove_all(dir);
}

// A/B: "Hold this image" keeps the image and its settings and turns the
// wipe on; an edit restarts the live render and leaves the held one alone.
TEST(Compare, HoldKeepsTheImageThroughAnEdit) {
  Scene scene = load_scene(resolve_scene("three-balls"));
  scene.camera.width = 16;
  scene.camera.height = 16;
  scene.settings.target_spp = 2;
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

// The camera stays in the room: wheel notches out from the cat's camera
// (z = 55, the back wall at z = 60) and drags that would orbit the eye
// under the floor stop short of the surface, and the eye stays inside.
TEST(CameraControl, WheelAndDragsKeepTheEyeInTheRoom) {
  const Scene cat = load_scene(resolve_scene("cat"));
  const World world(cat);
  std::string why;
  ASSERT_TRUE(eye_inside_room(cat.camera, world, &why)) << why;
  Camera c = cat.camera;
  MouseCamera mouse;
  MouseInput wheel;
  wheel.wheel = -1.0f;  // one notch out
  for (int k = 0; k < 10; ++k) {
    bool stopped = false;
    mouse.update(c, wheel, 1.0f, &world, &stopped);
    if (k == 0) {
      EXPECT_TRUE(stopped);
    }
    EXPECT_LT(c.position.z, 60.0) << "notch " << k;
    ASSERT_TRUE(eye_inside_room(c, world, &why)) << "notch " << k << ": " << why;
  }
  EXPECT_GT(c.position.z, 59.0);  // it went as far as the wall allows
  // A long left drag down: without the stop the eye orbits under the floor.
  Camera d = cat.camera;
  MouseInput press;
  press.clicked[0] = press.down[0] = true;
  mouse.update(d, press, 1.0f, &world);
  MouseInput drag;
  drag.down[0] = true;
  drag.dy = -25.0f;  // lowers the eye (orbit turns by -dy)
  for (int k = 0; k < 8; ++k) {
    mouse.update(d, drag, 1.0f, &world);
    ASSERT_TRUE(eye_inside_room(d, world, &why)) << "step " << k << ": " << why;
    // Above the floor: outside its sphere (centre (0, -1000, 0), radius 990).
    EXPECT_GT(glm::length(d.position - glm::dvec3(0.0, -1000.0, 0.0)), 990.0) << "step " << k;
  }
  // Without the World the same drag goes below the floor: the test can fail.
  Camera free = cat.camera;
  MouseCamera m2;
  m2.update(free, press, 1.0f);
  for (int k = 0; k < 8; ++k) m2.update(free, drag, 1.0f);
  EXPECT_FALSE(eye_inside_room(free, world));
}

TEST(CameraControl, AnEyeBehindTheWallIsReported) {
  const Scene cat = load_scene(resolve_scene("cat"));
  const World world(cat);
  Camera c = cat.camera;
  c.position.z = 61.1;  // one old wheel notch out
  std::string why;
  EXPECT_FALSE(eye_inside_room(c, world, &why));
  EXPECT_NE(why.find("behind a surface"), std::string::npos) << why;
}

// The window's image after an edit: the quick passes alone, then combined
// with the generation's own by count x fixed weight, then the own alone.
TEST(Blend, QuickThenCombinedThenTheOwnPassesAlone) {
  RenderSettings st;
  st.indirect = true;
  st.split = {4, 2};  // one own sample weighs 8 quick ones
  ASSERT_EQ(own_sample_weight(st), 8.0);
  Snapshot own, quick;
  own.width = quick.width = 1;
  own.height = quick.height = 1;
  quick.generation = 2;
  quick.spp = 4;
  quick.sum = {4.0f, 8.0f, 0.0f};  // mean 1, 2, 0
  own.generation = 1;
  own.spp = 3;
  own.sum = {30.0f, 30.0f, 30.0f};
  Shown out;
  blend_for_display(own, quick, st, out);  // the own passes are the old edit's
  EXPECT_EQ(out.quick_spp, 4u);
  EXPECT_EQ(out.image.mean(0, 0, 0), 1.0f);
  own.generation = 2;
  own.spp = 1;
  own.sum = {3.0f, 3.0f, 3.0f};  // mean 3
  blend_for_display(own, quick, st, out);
  // weights 8 x 1 own, 1 x 4 quick: (8 * 3 + 4 * 1) / 12, (8 * 3 + 4 * 2) / 12, 24 / 12
  EXPECT_FLOAT_EQ(out.image.mean(0, 0, 0), 28.0f / 12.0f);
  EXPECT_FLOAT_EQ(out.image.mean(0, 0, 1), 32.0f / 12.0f);
  EXPECT_FLOAT_EQ(out.image.mean(0, 0, 2), 2.0f);
  EXPECT_EQ(out.image.spp, 1u);
  EXPECT_EQ(out.quick_spp, 4u);
  own.spp = 8;  // 64 >= 16 x 4: the quick samples are dropped
  own.sum = {24.0f, 24.0f, 24.0f};
  blend_for_display(own, quick, st, out);
  EXPECT_EQ(out.quick_spp, 0u);
  EXPECT_EQ(out.image.sum, own.sum);
}
