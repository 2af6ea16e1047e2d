// The window loop: GLFW events, ImGui panel, renderer snapshots to the
// display. The loop never waits on the renderer: snapshot() returns at once.
#include "viewer/viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <numeric>
#include <string>

#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <imgui_internal.h>  // ClosePopupToLevel: Esc closes a dropdown

#include "io/image_io.h"
#include "io/stats_io.h"
#include "render/progressive.h"
#include "scene/scene_io.h"
#include "scene/world.h"
#include "viewer/camera_control.h"
#include "viewer/controller.h"
#include "viewer/display.h"
#include "viewer/event_log.h"
#include "viewer/input.h"
#include "viewer/overlay.h"
#include "viewer/scene_diff.h"
#include "viewer/screenshot.h"
#include "viewer/script.h"
#include "viewer/viewer_state.h"
#include "viewer/window.h"

namespace whisker {

namespace {


constexpr float kPanelWidth = 400.0f;  // window coordinates, before content scale
constexpr float kMinPanelWidth = 280.0f;  // the narrowest it gets in a small window

// The state of the open window between frames, and the steps of one frame.
struct Session {
  const ViewerOptions& opt;
  GLFWwindow* window;
  Display& display;
  Display& held_display;  // the A/B comparison's held image
  Display& debug_display;  // normals, material colours, depth
  Display& raw_display;    // the raw image left of a raw | denoised wipe
  ProgressiveRenderer& renderer;
  ViewerState& s;
  float panel_w;  // window units
  Controller ctl{renderer, s};
  ScriptedRun script{opt};
  MouseCamera mouse{};
  FrameStats fstats{};
  double next_check = 0.0;
  double last_frame = -1.0;
  std::uint64_t rse_generation = 0;
  std::uint64_t title_spp = ~0ull;
  std::uint64_t held_uploaded = ~0ull;  // version of the held image on the GPU
  std::uint64_t shown_count = 0, raw_uploaded = ~0ull;  // s.shown's changes, and the raw one on the GPU
  Scene debug_scene{};                   // what s.debug shows
  // The scene's geometry for the camera's collision rays (its BVH reused
  // while the meshes stay), and the scene it was built from.
  std::unique_ptr<World> room{};
  Scene room_scene{};
  Camera room_checked_camera{};
  glm::dvec3 room_checked_light{std::nan("")};
  int drawn = 0;
  static constexpr int kWarmupFrames = 5;
  // The denoised image (the Denoised box): filtered on a thread of its own.
  DenoisedView denoiser{[] { glfwPostEmptyEvent(); }};
  std::uint64_t denoise_asked = ~0ull;  // what was last handed to it

  // Wakes on input or ~60 times a second to look for a new pass; never
  // waits for one. The workers own the cores, so no busy loop either.
  double wait_for_events() {
    const double before = glfwGetTime();
    if (before < next_check)
      glfwWaitEventsTimeout(next_check - before);
    else
      glfwPollEvents();
    const double t0 = glfwGetTime();
    next_check = t0 + 1.0 / 60.0;
    return t0;
  }

  // Takes a new pass if there is one: to the GPU, and its error to the plot.
  bool take_snapshot() {
    const bool own = renderer.snapshot(s.snap);
    const bool quick = renderer.quick_snapshot(s.quick);
    if (!own && !quick) return false;
    blend_for_display(s.snap, s.quick, s.applied.settings, s.shown);
    ++shown_count;
    upload_image();
    if (!own) return true;
    s.nodes = s.snap.bvh_nodes;
    // Numbers come from the generation's own passes only.
    s.rse = s.snap.quick ? std::nan("") : s.snap.relative_standard_error();
    if (s.snap.generation != rse_generation) {
      s.rse_history.clear();
      rse_generation = s.snap.generation;
    }
    if (!s.snap.quick && std::isfinite(s.rse) && s.rse > 0.0) s.rse_history.push_back(float(std::log10(s.rse)));
    return true;
  }

  // The image on the GPU: what is shown (raw or denoised), or in the noise
  // view the own passes (their sums of squares belong to their sums).
  void upload_image() {
    if (s.display.mode == kViewNoise)
      display.upload(s.snap, true);
    else
      display.upload(showing_denoised(s) ? s.denoised : s.shown.image, false);
    uploaded_mode = s.display.mode == kViewNoise;
    uploaded_denoised = showing_denoised(s);
  }
  bool uploaded_mode = false, uploaded_denoised = false;

  // The quick passes' numbers are independent; Sobol halves are not.
  void ask_denoiser() {
    if (const Snapshot* src = denoise_source(s); src && denoise_key(s, *src) != denoise_asked) {
      denoise_asked = denoise_key(s, *src);
      denoiser.request(*src, src->quick || s.applied.settings.sampler == SamplerKind::Independent);
    }
  }

  // Draws the panel, reads the keys and the mouse, and carries out what they
  // ask. Returns where the image goes.
  PixelRect panel_and_input(const FrameSize& f, double t0) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();

    PanelRequests req;
    s.progress = renderer.pass_progress();
    update_debug_view();
    const int img_w = display.width() ? display.width() : s.applied.camera.width;
    const int img_h = display.height() ? display.height() : s.applied.camera.height;
    // The panel narrows, or steps aside, so that a small window still shows
    // the image as large as it can (viewer/layout.h).
    const PanelLayout lay = layout_panel(s.panel_mode, f.win_w, f.win_h, img_w / f.fb_per_win,
                                         img_h / f.fb_per_win, panel_w, kMinPanelWidth * panel_w / kPanelWidth);
    s.panel_visible = lay.visible;
    s.panel_overlay = lay.overlay;
    s.panel_width = lay.width;
    draw_panel(s, f.win_w, f.win_h, lay.width, t0, req);
    if (tooltip_waiting()) request_redraw();  // the tooltip shows when the rest is long enough

    // The render area is what the panel leaves, in framebuffer pixels.
    const int panel_fb = lay.overlay ? 0 : int(std::lround(lay.width * f.fb_per_win));
    const PixelRect area{0, 0, std::max(0, f.fb_w - panel_fb), f.fb_h};
    const PixelRect rect = fit_image(area, img_w, img_h);

    map_keys(read_keys(), imgui_wants_keyboard(), imgui_popup_open(), req);
    if (req.close_popups) {
      ImGui::ClosePopupToLevel(0, true);
      s.pending_load.clear();
      s.pending_quit = false;
    }
    req.typing = ImGui::GetIO().WantTextInput && ImGui::IsAnyItemActive();
    req.editing = ImGui::IsAnyItemActive() || ImGui::IsAnyMouseDown();
    // A held mouse button (an orbit, a slider) makes edits faster than
    // full-resolution quick passes: coarse ones follow it (set_dragging).
    renderer.set_dragging(ImGui::IsAnyMouseDown());
    const std::string dropped = take_dropped_file();
    if (!dropped.empty()) {
      std::string error;
      request_for_drop(dropped, req, error);
      if (!error.empty()) s.message = error, s.message_is_error = true;
    }
    // Image pixels per window unit, so a pan drags the scene with the mouse.
    const float image_scale = img_w > 0 ? rect.w / (f.fb_per_win * img_w) : 1.0f;
    update_room();
    bool stopped = false;
    mouse.update(s.edited.camera, read_mouse(), image_scale > 0.0f ? image_scale : 1.0f,
                 room.get(), &stopped);
    if (stopped) {
      s.message = kCameraStopped;
      s.message_is_error = false;
    }

    ctl.carry_out(req, t0);
    if (req.quit) glfwSetWindowShouldClose(window, GLFW_TRUE);
    if (req.confirm_quit) {
      quit_confirmed = true;
      glfwSetWindowShouldClose(window, GLFW_TRUE);
    }
    if (s.held.spp > 0 && s.held.version != held_uploaded) {
      held_display.upload(s.held, true);
      held_uploaded = s.held.version;
    }
    // Over the image: legend, wipe line, the pixel under the mouse (not in a
    // scripted screenshot, which compares with the headless render).
    image_area = {rect.x / f.fb_per_win, rect.y / f.fb_per_win, rect.w / f.fb_per_win,
                  rect.h / f.fb_per_win};
    draw_image_overlays(s, image_area, opt.screenshot_path.empty() && s.readout_on, &readout);
    // Switching to the noise view needs the sums of squares on the GPU.
    if ((s.display.mode == kViewNoise) != uploaded_mode) upload_image();
    return rect;
  }

  // The World for the camera's rays follows the edited scene's geometry; the
  // eye's place is checked whenever the applied camera changes.
  void update_room() {
    Scene geometry = s.edited;
    geometry.camera = room_scene.camera;
    geometry.light = room_scene.light;
    geometry.settings = room_scene.settings;
    if (!room || classify_change(room_scene, geometry) != SceneChange::None) {
      room = std::make_unique<World>(s.edited, room.get());
      room_scene = s.edited;
      room_checked_camera = Camera{};
      room_checked_camera.width = -1;  // checked again below
      room_checked_light = glm::dvec3(std::nan(""));
    }
    const Camera& c = s.applied.camera;
    if (c.position != room_checked_camera.position || c.look_at != room_checked_camera.look_at ||
        c.width != room_checked_camera.width) {
      room_checked_camera = c;
      std::string why;
      s.eye_outside = eye_inside_room(c, *room, &why) ? std::string() : why;
    }
    const glm::dvec3 light = s.applied.light.position;
    if (light != room_checked_light) {
      room_checked_light = light;
      std::string why;
      s.light_outside = inside_room(light, glm::dvec3(0, -1, 0), *room, "the light", &why) ? std::string() : why;
    }
  }

  // A debug view follows the applied scene (camera moves included).
  void update_debug_view() {
    if (s.display.mode < kViewNormals) return;
    if (s.debug.view == s.display.mode && classify_change(debug_scene, s.applied) == SceneChange::None)
      return;
    s.debug = render_debug_view(s.applied, s.display.mode);
    debug_scene = s.applied;
    debug_display.upload(s.debug.image, false);
  }

  // The samples per pixel of the current settings' own passes, as the
  // panel's bar said them this frame (0 until the first lands). The panel
  // is drawn before the frame's edits are carried out, so the title takes
  // the bar's number rather than counting again after them: in an edit's
  // frame it said 0 spp while the bar still showed the old render's 5.
  void update_title() {
    const std::uint64_t spp = s.bar_spp;
    if (spp == title_spp) return;
    title_spp = spp;
    const std::string title = "Whisker - " + s.scene_label + " - " + std::to_string(spp) + " spp";
    glfwSetWindowTitle(window, title.c_str());
  }

  void render(const FrameSize& f, const PixelRect& rect) {
    ImGui::Render();
    glViewport(0, 0, f.fb_w, f.fb_h);
    glClearColor(0.12f, 0.12f, 0.13f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    s.display.exposure = report_exposure() * std::exp2(s.exposure_stops);
    const bool held = s.held.spp > 0 && held_display.width() > 0;
    if (s.display.mode >= kViewNormals) {
      debug_display.draw(rect, f.fb_h, 1.0f, DisplayParams{1.0f, 1.0f, 0, 0});
    } else if (held && s.compare == kCompareHeld) {
      held_display.draw(rect, f.fb_h, float(s.held.spp), s.display);
    } else {
      const Snapshot& live = s.display.mode == kViewNoise ? s.snap
                             : showing_denoised(s)           ? s.denoised
                                                             : s.shown.image;
      display.draw(rect, f.fb_h, float(live.spp), s.display);
      if (held && s.compare == kCompareWipe)
        held_display.draw_columns(rect, f.fb_h, float(s.held.spp), s.display, 0.0f, s.wipe);
      if (s.display.mode == kViewImage && s.compare == kCompareRawDenoised && wipe_left(s)) {
        if (raw_uploaded != shown_count) raw_display.upload(s.shown.image, false);
        raw_uploaded = shown_count;
        raw_display.draw_columns(rect, f.fb_h, float(s.shown.image.spp), s.display, 0.0f, s.wipe);
      }
    }
    glViewport(0, 0, f.fb_w, f.fb_h);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }

  // Timings leave out the first frames (font atlas, llvmpipe compiling the
  // shaders, the first texture allocation) and the screenshot's. The panel
  // shows the mean of the last 30 timed frames.
  void record_timing(double t0, double t_work, double t1, bool finish) {
    if (++drawn > kWarmupFrames && !finish) {
      fstats.work_ms.push_back(float((t_work - t0) * 1e3));
      fstats.total_ms.push_back(float((t1 - t0) * 1e3));
    }
    if (!fstats.total_ms.empty()) {
      const std::size_t n = std::min<std::size_t>(30, fstats.total_ms.size());
      s.frame_ms_avg = std::accumulate(fstats.total_ms.end() - n, fstats.total_ms.end(), 0.0f) / n;
    }
  }

  // --edit-log: what each drawn frame showed (viewer/event_log.h).
  EventLog log{};
  ReadoutShown readout{};  // the pixel readout drawn this frame
  ImageArea image_area{};  // where the image is, in window units

  // Esc, Quit or the window's close button: with unsaved edits the panel
  // asks first (confirm_quit_popup), and the window stays until it is told.
  bool quit_confirmed = false;
  bool should_close() {
    if (!glfwWindowShouldClose(window)) return false;
    if (quit_confirmed || !ctl.edits_unsaved()) return true;
    glfwSetWindowShouldClose(window, GLFW_FALSE);
    s.pending_quit = true;
    request_redraw();
    return false;
  }

  // Runs until the window closes or the scripted run is done; the exit code.
  int run() {
    int exit_code = 0;
    while (!should_close()) {
      const double t0 = wait_for_events();
      bool fresh = take_snapshot();
      ctl.stop_when_reached();
      ask_denoiser();
      if (denoiser.latest(s.denoised, s.denoised_figures) || showing_denoised(s) != uploaded_denoised) {
        upload_image();
        fresh = true;
      }
      // Draw only when the screen can change: a new pass, input (and a few
      // frames after it for ImGui to settle), or the panel's clock.
      if (!fresh && !redraw_pending() && t0 - last_frame < 0.5) continue;
      take_redraw();
      last_frame = t0;

      script.apply_due_edit(s);
      const FrameSize f = frame_size(window);
      const PixelRect rect = panel_and_input(f, t0);
      // Without --screenshot the window stays open after --frames passes
      // (the target stops the render there).
      const bool finish = (!opt.screenshot_path.empty() || !opt.event_log.empty()) &&
                          script.finished(s) && denoised_caught_up(s);
      update_title();
      render(f, rect);

      const double t_work = glfwGetTime();
      if (finish && !opt.screenshot_path.empty() && !take_screenshot(opt.screenshot_path, rect, s, fstats, f.fb_w, f.fb_h))
        exit_code = 2;  // an output that cannot be written, as headless
      glfwSwapBuffers(window);
      log.frame(s, t0, glfwGetTime(), title_spp, readout, image_area);
      record_timing(t0, t_work, glfwGetTime(), finish);
      if (finish) break;
    }
    return exit_code;
  }

  // One closing line: what was rendered, and how many times the render
  // restarted (the generation), which scripted input tests read.
  void print_summary() const {
    std::fprintf(stderr,
                 "viewer: %s, generation %llu, %llu passes, %llu spp, %.2f passes/s; UI %zu "
                 "frames, mean %.2f ms, p95 %.2f ms\n",
                 s.scene_label.c_str(), (unsigned long long)s.generation,
                 (unsigned long long)s.snap.counters.passes, (unsigned long long)s.snap.spp,
                 s.snap.counters.seconds > 0 ? s.snap.counters.passes / s.snap.counters.seconds : 0.0,
                 fstats.total_ms.size(), FrameStats::mean(fstats.total_ms),
                 FrameStats::pct(fstats.total_ms, 0.95));
  }
};

}  // namespace

bool display_available() {
  const GlfwSession glfw;
  return glfw.ok();
}

int run_viewer(const ViewerOptions& opt) {
  const GlfwSession glfw;
  if (!glfw.ok()) {
    std::fprintf(stderr, "whisker: cannot open a window: no display (%s).\n",
                 last_glfw_error().c_str());
    return 3;  // the caller suggests --headless
  }
  int win_w = 0, win_h = 0;
  initial_window_size(opt.scene.camera.width, opt.scene.camera.height, opt.width, opt.height,
                      kPanelWidth, win_w, win_h);
  const Window window(win_w, win_h, "Whisker");
  if (!window.error().empty()) {
    std::fprintf(stderr, "whisker: %s\n", window.error().c_str());
    return 3;
  }
  Display display, held_display, debug_display, raw_display;
  std::string error;
  if (!display.init(error) || !held_display.init(error) || !debug_display.init(error) ||
      !raw_display.init(error)) {
    std::fprintf(stderr, "whisker: %s\n", error.c_str());
    return 1;
  }
  const ImGuiSession imgui(window.handle());
  // A scripted screenshot shows the panel as it is, not a tooltip under
  // wherever the pointer happens to rest.
  if (!opt.screenshot_path.empty()) ImGui::GetIO().ConfigFlags |= ImGuiConfigFlags_NoMouse;

  ViewerState s;
  init_state(s, opt.scene, opt.scene_path);
  ScriptedRun(opt).prepare(s);

  ProgressiveRenderer renderer(opt.threads);
  s.threads = renderer.threads();
  // Quick passes show an edit at once (viewer/blend.h); they never enter the
  // accumulation, so scripted runs compare with headless renders as before.
  // A scripted screenshot compares with the headless render after its
  // passes, so it shows the own passes alone.
  renderer.set_quick_passes(opt.screenshot_path.empty());
  renderer.set_growing_passes(opt.screenshot_path.empty());
  // A deterministic estimate is exact after one pass; a scripted run renders
  // its --frames passes, as the headless mode with --frames does.
  renderer.set_stop_when_exact(opt.frames <= 0);
  renderer.set_low_priority(true);  // the UI thread shares the two cores
  // The denoised view's feature buffers, from the first generation on.
  renderer.set_features(true);
  s.denoised_view = opt.denoised;
  // A published pass wakes the event loop at once, not at its next check.
  renderer.set_on_publish([] { glfwPostEmptyEvent(); });
  s.generation = renderer.set_scene(s.applied);
  renderer.start();
  s.last_change = glfwGetTime();

  Session session{opt, window.handle(), display, held_display, debug_display, raw_display, renderer, s,
                  kPanelWidth * imgui.ui_scale()};
  if (!opt.event_log.empty()) {
    if (!session.log.open(opt.event_log)) {
      std::fprintf(stderr, "whisker: --edit-log %s: cannot write it\n", opt.event_log.c_str());
      renderer.stop();
      return 2;
    }
  }
  const int exit_code = session.run();
  session.print_summary();
  renderer.stop();
  return exit_code;
}

}  // namespace whisker
