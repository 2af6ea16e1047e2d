// The window loop: GLFW events, ImGui panel, renderer snapshots to the
// display. The loop never waits on the renderer: snapshot() returns at once.
#include "viewer/viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <numeric>
#include <string>

#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "geometry/bvh.h"
#include "render/image_io.h"
#include "render/progressive.h"
#include "render/stats_io.h"
#include "scene/scene_io.h"
#include "viewer/camera_control.h"
#include "viewer/display.h"
#include "viewer/scene_diff.h"
#include "viewer/viewer_state.h"

namespace whisker {

namespace {

std::string g_glfw_error;
int g_redraw = 0;  // frames to draw because of input

// Input marks the window for redrawing. Installed before ImGui's backend,
// which chains to them.
void mark_redraw() { g_redraw = 3; }
void install_redraw_callbacks(GLFWwindow* w) {
  glfwSetCursorPosCallback(w, [](GLFWwindow*, double, double) { mark_redraw(); });
  glfwSetMouseButtonCallback(w, [](GLFWwindow*, int, int, int) { mark_redraw(); });
  glfwSetScrollCallback(w, [](GLFWwindow*, double, double) { mark_redraw(); });
  glfwSetKeyCallback(w, [](GLFWwindow*, int, int, int, int) { mark_redraw(); });
  glfwSetCharCallback(w, [](GLFWwindow*, unsigned) { mark_redraw(); });
  glfwSetCursorEnterCallback(w, [](GLFWwindow*, int) { mark_redraw(); });
  glfwSetWindowFocusCallback(w, [](GLFWwindow*, int) { mark_redraw(); });
  glfwSetFramebufferSizeCallback(w, [](GLFWwindow*, int, int) { mark_redraw(); });
  glfwSetWindowRefreshCallback(w, [](GLFWwindow*) { mark_redraw(); });
}

void on_glfw_error(int code, const char* text) {
  g_glfw_error = std::string(text ? text : "") + " (GLFW error " + std::to_string(code) + ")";
}

constexpr float kPanelWidth = 400.0f;  // window coordinates, before content scale

std::string scene_label_of(const Scene& scene, const std::string& path) {
  if (!scene.name.empty()) return scene.name;
  if (!path.empty()) return std::filesystem::path(path).stem().string();
  return "scene";
}

// The loop's actions on the renderer; every restart goes through here.
struct Controller {
  ProgressiveRenderer& renderer;
  ViewerState& s;

  // Hands the panel's edits to the renderer if a value really changed.
  void apply_edits(double now) {
    switch (classify_change(s.applied, s.edited)) {
      case SceneChange::None:
        return;
      case SceneChange::Settings:
        s.generation = renderer.set_settings(s.edited.settings);
        break;
      case SceneChange::Scene:
        s.generation = renderer.set_scene(s.edited);
        break;
    }
    s.applied = s.edited;
    s.last_change = now;
  }

  void restart(double now) {
    s.generation = renderer.set_scene(s.applied);
    s.last_change = now;
  }

  void load(const std::string& name_or_path, double now) {
    try {
      const std::filesystem::path path = resolve_scene(name_or_path);
      Scene scene = load_scene(path);
      s.initial = scene;
      s.edited = scene;
      s.applied = scene;
      s.scene_label = scene_label_of(scene, path.string());
      s.path_field = path.string();
      s.generation = renderer.set_scene(scene);
      s.last_change = now;
      s.message = "loaded " + path.string();
      s.message_is_error = false;
    } catch (const std::exception& e) {
      s.message = e.what();
      s.message_is_error = true;
    }
  }

  void save() {
    const Snapshot& sn = s.snap;
    if (sn.spp == 0 || sn.preview) {
      s.message = "nothing to save yet";
      s.message_is_error = true;
      return;
    }
    const std::string base = (std::filesystem::path(s.save_dir) /
                              (s.scene_label + "-" + std::to_string(sn.spp) + "spp"))
                                 .string();
    try {
      const Image img = mean_image(sn);
      write_png(base + ".png", img);
      const std::string float_path = base + (have_exr() ? ".exr" : ".pfm");
      write_float_image(float_path, img);
      s.message = "saved " + base + ".png and " + float_path;
      s.message_is_error = false;
      std::printf("%s\n", s.message.c_str());
      std::fflush(stdout);
    } catch (const std::exception& e) {
      s.message = std::string("save failed: ") + e.what();
      s.message_is_error = true;
    }
  }
};

struct MouseCamera {
  bool dragging[3] = {false, false, false};

  // Left: orbit, right/middle: pan, wheel: dolly. A drag that starts over the
  // panel belongs to ImGui (WantCaptureMouse) and never moves the camera.
  void update(Camera& cam, float image_scale) {
    ImGuiIO& io = ImGui::GetIO();
    for (int b = 0; b < 3; ++b) {
      if (ImGui::IsMouseClicked(b)) dragging[b] = !io.WantCaptureMouse;
      if (!ImGui::IsMouseDown(b)) dragging[b] = false;
    }
    const ImVec2 d = io.MouseDelta;
    const bool moved = (d.x != 0.0f || d.y != 0.0f) && std::isfinite(d.x) && std::isfinite(d.y);
    if (moved && dragging[0]) orbit(cam, -d.x * 0.008f, -d.y * 0.008f);
    if (moved && (dragging[1] || dragging[2]))
      pan(cam, d.x / image_scale, d.y / image_scale);
    if (io.MouseWheel != 0.0f && !io.WantCaptureMouse)
      dolly(cam, std::pow(0.9f, io.MouseWheel));
  }
};

void print_camera(const Camera& cam) {
  std::printf("%s\n", camera_to_json(cam).c_str());
  std::fflush(stdout);
}

struct FrameStats {
  std::vector<float> work_ms, total_ms;
  static float mean(const std::vector<float>& v) {
    return v.empty() ? 0.0f : std::accumulate(v.begin(), v.end(), 0.0f) / v.size();
  }
  static float pct(std::vector<float> v, double p) {
    if (v.empty()) return 0.0f;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(p * (v.size() - 1) + 0.5))];
  }
};

// A summary next to a scripted screenshot (<screenshot>.json): what was
// rendered (the shared stats record), where the render area is, how fast the
// UI ran.
void write_summary(const std::string& path, const PixelRect& r, const ViewerState& s,
                   const FrameStats& f, int fb_w, int fb_h) {
  using V = std::vector<long long>;
  RenderStats st{s.scene_label, &s.snap, s.threads, &s.applied.settings, {}};
  const float max_ms =
      f.total_ms.empty() ? 0.0f : *std::max_element(f.total_ms.begin(), f.total_ms.end());
  st.extra = {{"framebuffer", V{fb_w, fb_h}},
              {"render_rect", V{r.x, r.y, r.w, r.h}},
              {"ui_frames", (long long)f.total_ms.size()},
              {"ui_frame_ms_mean", double(FrameStats::mean(f.total_ms))},
              {"ui_frame_ms_p95", double(FrameStats::pct(f.total_ms, 0.95))},
              {"ui_frame_ms_max", double(max_ms)},
              {"ui_frame_work_ms_mean", double(FrameStats::mean(f.work_ms))}};
  write_stats_json(path, st);
}

}  // namespace

bool display_available() {
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) return false;
  glfwTerminate();
  return true;
}

int run_viewer(const ViewerOptions& opt) {
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) {
    std::fprintf(stderr,
                 "whisker: cannot open a window: no display (%s).\n",
                 g_glfw_error.c_str());
    return 3;  // the caller suggests --headless
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);

  // Sizes are asked for in logical units: GLFW_SCALE_TO_MONITOR multiplies
  // them by the content scale on X11 and Windows, macOS doubles the
  // framebuffer instead. Either way the image gets its pixels 1:1.
  float cscale = 1.0f;
  int max_w = 1 << 14, max_h = 1 << 14;
  if (GLFWmonitor* mon = glfwGetPrimaryMonitor()) {
    float sy = 1.0f;
    glfwGetMonitorContentScale(mon, &cscale, &sy);
    if (const GLFWvidmode* mode = glfwGetVideoMode(mon)) {
      max_w = mode->width;
      max_h = mode->height;
    }
  }
  cscale = std::clamp(cscale, 1.0f, 4.0f);
  const Camera& cam0 = opt.scene.camera;
  int win_w = opt.width > 0 ? opt.width : int(cam0.width / cscale + kPanelWidth);
  int win_h = opt.height > 0 ? opt.height : std::max(int(cam0.height / cscale), 800);
  win_w = std::min(win_w, int(max_w / cscale));
  win_h = std::min(win_h, int(max_h / cscale));

  GLFWwindow* window = glfwCreateWindow(win_w, win_h, "Whisker", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr,
                 "whisker: cannot open an OpenGL 3.3 core window (%s).\n",
                 g_glfw_error.c_str());
    glfwTerminate();
    return 3;
  }
  glfwMakeContextCurrent(window);
  if (!gladLoadGL(glfwGetProcAddress)) {
    std::fprintf(stderr, "whisker: cannot load OpenGL 3.3 functions.\n");
    glfwDestroyWindow(window);
    glfwTerminate();
    return 3;
  }
  glfwSwapInterval(1);

  int exit_code = 0;
  {
    Display display;
    std::string error;
    if (!display.init(error)) {
      std::fprintf(stderr, "whisker: %s\n", error.c_str());
      glfwDestroyWindow(window);
      glfwTerminate();
      return 1;
    }

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // the panel is fixed; nothing to remember
    ImGui::StyleColorsDark();
    // The panel scales by whatever the framebuffer does not already: the
    // content scale on X11/Windows, nothing more on macOS.
    float ui_scale = 1.0f;
    {
      float sx = 1.0f, sy = 1.0f;
      glfwGetWindowContentScale(window, &sx, &sy);
      int fw = 0, fh = 0, ww = 0, wh = 0;
      glfwGetFramebufferSize(window, &fw, &fh);
      glfwGetWindowSize(window, &ww, &wh);
      const float fb_ratio = ww > 0 && fw > 0 ? float(fw) / ww : 1.0f;
      ui_scale = std::clamp(sx / fb_ratio, 1.0f, 4.0f);
    }
    const float panel_w = kPanelWidth * ui_scale;
    ImGui::GetStyle().ScaleAllSizes(ui_scale);
    io.FontGlobalScale = ui_scale;
    install_redraw_callbacks(window);
    g_redraw = 3;
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330");

    ViewerState s;
    s.initial = s.applied = s.edited = opt.scene;
    s.scene_label = scene_label_of(opt.scene, opt.scene_path);
    s.path_field = opt.scene_path;
    try {
      s.scene_names = list_scenes();
    } catch (const std::exception& e) {
      s.message = e.what();
      s.message_is_error = true;
    }

    // A scripted run renders exactly `frames` passes of its last generation,
    // as the headless mode does, so its screenshot compares with that render.
    if (opt.frames > 0) {
      s.initial.settings.target_spp = opt.frames * std::max(1, opt.scene.settings.spp);
      s.applied = s.edited = s.initial;
    }

    ProgressiveRenderer renderer(opt.threads);
    s.threads = renderer.threads();
    // A coarse preview (1/16 of a pass) shows an edit at once; it is never
    // accumulated, so scripted runs and saves skip it.
    renderer.set_preview(true);
    renderer.set_low_priority(true);  // the UI thread shares the two cores
    Controller ctl{renderer, s};
    s.generation = renderer.set_scene(s.applied);
    renderer.start();
    s.last_change = glfwGetTime();

    MouseCamera mouse;
    FrameStats fstats;
    std::size_t next_edit = 0;
    double next_check = 0.0;
    bool finish = false;
    std::uint64_t title_spp = ~0ull;

    double last_frame = -1.0;
    std::uint64_t rse_generation = 0;
    int drawn = 0;
    constexpr int kWarmupFrames = 5;
    while (!glfwWindowShouldClose(window)) {
      // Wake on input or ~60 times a second to look for a new pass; never
      // wait for one. The workers own the cores, so no busy loop either.
      const double before = glfwGetTime();
      if (before < next_check)
        glfwWaitEventsTimeout(next_check - before);
      else
        glfwPollEvents();
      const double t0 = glfwGetTime();
      next_check = t0 + 1.0 / 60.0;

      const bool fresh = renderer.snapshot(s.snap);
      if (fresh) {
        s.triangles = s.snap.triangles;
        s.nodes = s.snap.bvh_nodes;
        display.upload(s.snap, s.display.mode == 1);
        s.rse = s.snap.preview ? std::nan("") : s.snap.relative_standard_error();
        if (s.snap.generation != rse_generation) {
          s.rse_history.clear();
          rse_generation = s.snap.generation;
        }
        if (!s.snap.preview && std::isfinite(s.rse) && s.rse > 0.0) s.rse_history.push_back(float(std::log10(s.rse)));
      }
      // Draw only when the screen can change: a new pass, input (and a few
      // frames after it for ImGui to settle), or the panel's clock.
      if (!fresh && g_redraw <= 0 && t0 - last_frame < 0.5) continue;
      if (g_redraw > 0) --g_redraw;
      last_frame = t0;

      // Scripted edits go through the same path as the panel's.
      if (next_edit < opt.edits.size() && s.snap.generation == s.generation && !s.snap.preview &&
          (s.snap.passes >= std::uint64_t(std::max(0, opt.edits[next_edit].after_pass)) ||
           s.snap.done)) {
        if (opt.edits[next_edit].light_position)
          s.edited.light.position = *opt.edits[next_edit].light_position;
        ++next_edit;
      }

      int fb_w = 0, fb_h = 0;
      glfwGetFramebufferSize(window, &fb_w, &fb_h);
      int ww = 0, wh = 0;
      glfwGetWindowSize(window, &ww, &wh);
      const float fb_per_win = ww > 0 ? float(fb_w) / ww : 1.0f;

      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();

      PanelRequests req;
      draw_panel(s, float(ww), float(wh), std::min(panel_w, float(ww)), t0, req);

      // The render area is what the panel leaves, in framebuffer pixels.
      const int panel_fb = int(std::lround(std::min(panel_w, float(ww)) * fb_per_win));
      const PixelRect area{0, 0, std::max(0, fb_w - panel_fb), fb_h};
      const int img_w = display.width() ? display.width() : s.applied.camera.width;
      const int img_h = display.height() ? display.height() : s.applied.camera.height;
      const PixelRect rect = fit_image(area, img_w, img_h);

      // Keys act unless ImGui is taking text input.
      if (!io.WantCaptureKeyboard) {
        if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) req.toggle_pause = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_R, false)) req.restart = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_S, false)) req.save = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_C, false)) req.print_camera = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) req.quit = true;
      }
      // Image pixels per window unit, so a pan drags the scene with the mouse.
      const float image_scale = img_w > 0 ? rect.w / (fb_per_win * img_w) : 1.0f;
      mouse.update(s.edited.camera, image_scale > 0.0f ? image_scale : 1.0f);

      if (req.reset_camera) s.edited.camera = s.initial.camera;
      if (req.threads > 0) {
        renderer.set_threads(req.threads);
        s.threads = renderer.threads();
      }
      if (!req.load_scene.empty()) ctl.load(req.load_scene, t0);
      ctl.apply_edits(t0);
      if (req.restart) ctl.restart(t0);
      if (req.toggle_pause) {
        s.paused = !s.paused;
        renderer.set_paused(s.paused);
      }
      if (req.save) ctl.save();
      if (req.print_camera) print_camera(s.applied.camera);
      if (req.quit) glfwSetWindowShouldClose(window, GLFW_TRUE);
      // Switching to the noise view needs the sums of squares on the GPU.
      if (s.display.mode == 1 && !display.has_sq() && s.snap.spp) display.upload(s.snap, true);

      if (opt.frames > 0 && next_edit == opt.edits.size() &&
          s.snap.generation == s.generation && !s.snap.preview &&
          (s.snap.passes >= std::uint64_t(opt.frames) || s.snap.done))
        finish = true;

      if (s.snap.spp != title_spp) {
        title_spp = s.snap.spp;
        const std::string title = "Whisker - " + s.scene_label + " - " +
                                  std::to_string(s.snap.spp) + " spp";
        glfwSetWindowTitle(window, title.c_str());
      }

      ImGui::Render();
      glViewport(0, 0, fb_w, fb_h);
      glClearColor(0.12f, 0.12f, 0.13f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT);
      s.display.exposure = report_exposure() * std::exp2(s.exposure_stops);
      display.draw(rect, fb_h, float(s.snap.spp), s.display);
      glViewport(0, 0, fb_w, fb_h);
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

      const double t_work = glfwGetTime();
      if (finish && !opt.screenshot_path.empty()) {
        const auto pixels = read_framebuffer(fb_w, fb_h);
        try {
          write_png_rgb8(opt.screenshot_path, fb_w, fb_h, pixels);
          write_summary(opt.screenshot_path + ".json", rect, s, fstats, fb_w, fb_h);
        } catch (const ImageError& e) {
          std::fprintf(stderr, "whisker: %s\n", e.what());
          exit_code = 1;
        }
      }
      glfwSwapBuffers(window);
      const double t1 = glfwGetTime();
      // Timings leave out the first frames (font atlas, llvmpipe compiling
      // the shaders, the first texture allocation) and the screenshot's.
      if (++drawn > kWarmupFrames && !finish) {
        fstats.work_ms.push_back(float((t_work - t0) * 1e3));
        fstats.total_ms.push_back(float((t1 - t0) * 1e3));
      }
      // The panel shows the mean of the last 30 timed frames.
      if (!fstats.total_ms.empty()) {
        const std::size_t n = std::min<std::size_t>(30, fstats.total_ms.size());
        s.frame_ms_avg = std::accumulate(fstats.total_ms.end() - n, fstats.total_ms.end(), 0.0f) / n;
      }
      if (finish) break;
    }

    // One closing line: what was rendered, and how many times the render
    // restarted (the generation), which scripted input tests read.
    std::fprintf(stderr,
                 "viewer: %s, generation %llu, %llu passes, %llu spp, %.2f passes/s; UI %zu "
                 "frames, mean %.2f ms, p95 %.2f ms\n",
                 s.scene_label.c_str(), (unsigned long long)s.generation,
                 (unsigned long long)s.snap.passes, (unsigned long long)s.snap.spp,
                 s.snap.seconds > 0 ? s.snap.passes / s.snap.seconds : 0.0,
                 fstats.total_ms.size(), FrameStats::mean(fstats.total_ms),
                 FrameStats::pct(fstats.total_ms, 0.95));
    renderer.stop();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return exit_code;
}

}  // namespace whisker
