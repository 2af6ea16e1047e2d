#include <string>
#include "viewer/window.h"

#include <algorithm>
#include <cstring>

#include <dlfcn.h>
#include <link.h>

#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

namespace whisker {

namespace {

std::string g_glfw_error;
int g_redraw = 0;  // frames to draw because of input
std::string g_dropped;  // the last file dropped on the window
std::vector<KeyPress> g_key_presses;
float g_press[3][2] = {};  // press_position()

void on_glfw_error(int code, const char* text) {
  g_glfw_error = std::string(text ? text : "") + " (GLFW error " + std::to_string(code) + ")";
}

// In an ASan build (WHISKER_SANITIZE=address), pins the OpenGL driver the
// context loaded (Mesa's *_dri.so or libgallium) so that it is never
// unloaded. LeakSanitizer checks at exit, after glfwTerminate has unloaded
// the driver: the memory its globals still held then reads as leaked, from
// stack frames no longer mapped, which no suppression can name
// (tests/sanitizers/lsan.supp). Pinned, its globals stay roots.
#if defined(__SANITIZE_ADDRESS__)
#define WHISKER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define WHISKER_ASAN 1
#endif
#endif
#ifdef WHISKER_ASAN
void pin_gl_driver() {
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) {
        const char* name = info->dlpi_name;
        if (name && (std::strstr(name, "_dri.so") || std::strstr(name, "libgallium")))
          dlopen(name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        return 0;
      },
      nullptr);
}
#else
void pin_gl_driver() {}
#endif

// Input marks the window for redrawing. Installed before ImGui's backend,
// which chains to them.
void mark_redraw() { g_redraw = 3; }
void install_redraw_callbacks(GLFWwindow* w) {
  glfwSetCursorPosCallback(w, [](GLFWwindow*, double, double) { mark_redraw(); });
  glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int) {
    if (action == GLFW_PRESS && button >= 0 && button < 3) {
      double x = 0.0, y = 0.0;
      glfwGetCursorPos(win, &x, &y);
      g_press[button][0] = float(x);
      g_press[button][1] = float(y);
    }
    mark_redraw();
  });
  glfwSetScrollCallback(w, [](GLFWwindow*, double, double) { mark_redraw(); });
  glfwSetKeyCallback(w, [](GLFWwindow*, int key, int, int action, int mods) {
    // Every press, in order, even one released before the next frame:
    // the shortcuts read these rather than ImGui's per-frame key state.
    // A Tab reaches here only while a field is typed into (ImGuiSession's
    // callback keeps the others from ImGui and queues them itself): it is
    // the field's, never the panel's shortcut.
    if (key != GLFW_KEY_TAB && (action == GLFW_PRESS || action == GLFW_REPEAT))
      g_key_presses.push_back({key, mods, action == GLFW_REPEAT});
    mark_redraw();
  });
  glfwSetCharCallback(w, [](GLFWwindow*, unsigned) { mark_redraw(); });
  glfwSetCursorEnterCallback(w, [](GLFWwindow*, int) { mark_redraw(); });
  glfwSetWindowFocusCallback(w, [](GLFWwindow*, int) { mark_redraw(); });
  glfwSetFramebufferSizeCallback(w, [](GLFWwindow*, int, int) { mark_redraw(); });
  glfwSetWindowRefreshCallback(w, [](GLFWwindow*) { mark_redraw(); });
  glfwSetDropCallback(w, [](GLFWwindow*, int count, const char** paths) {
    if (count > 0 && paths[0]) g_dropped = paths[0];
    mark_redraw();
  });
}

}  // namespace

const std::string& last_glfw_error() { return g_glfw_error; }

std::vector<KeyPress> take_key_presses() {
  std::vector<KeyPress> keys;
  keys.swap(g_key_presses);
  return keys;
}

void put_back_key_presses(const std::vector<KeyPress>& keys) {
  if (keys.empty()) return;
  g_key_presses.insert(g_key_presses.begin(), keys.begin(), keys.end());
  mark_redraw();
}

std::string take_dropped_file() {
  std::string path;
  path.swap(g_dropped);
  return path;
}

void press_position(int b, float& x, float& y) {
  x = g_press[b][0];
  y = g_press[b][1];
}

void request_redraw() { mark_redraw(); }

bool redraw_pending() { return g_redraw > 0; }
void take_redraw() {
  if (g_redraw > 0) --g_redraw;
}

GlfwSession::GlfwSession() {
  glfwSetErrorCallback(on_glfw_error);
  ok_ = glfwInit() == GLFW_TRUE;
}

GlfwSession::~GlfwSession() {
  if (ok_) glfwTerminate();
}

void initial_window_size(int image_w, int image_h, int asked_w, int asked_h, float panel_width,
                         int& width, int& height) {
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
  width = asked_w > 0 ? asked_w : int(image_w / cscale + panel_width);
  height = asked_h > 0 ? asked_h : std::max(int(image_h / cscale), 800);
  width = std::min(width, int(max_w / cscale));
  height = std::min(height, int(max_h / cscale));
}

Window::Window(int width, int height, const char* title) {
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title, nullptr, nullptr);
  if (!window_) {
    error_ = "cannot open an OpenGL 3.3 core window (" + g_glfw_error + ").";
    return;
  }
  glfwMakeContextCurrent(window_);
  if (!gladLoadGL(glfwGetProcAddress)) {
    error_ = "cannot load OpenGL 3.3 functions.";
    return;
  }
  pin_gl_driver();
  glfwSwapInterval(1);
}

Window::~Window() {
  if (window_) glfwDestroyWindow(window_);
}

ImGuiSession::ImGuiSession(GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the panel is fixed; nothing to remember
  ImGui::StyleColorsDark();
  // The panel scales by whatever the framebuffer does not already: the
  // content scale on X11/Windows, nothing more on macOS.
  float sx = 1.0f, sy = 1.0f;
  glfwGetWindowContentScale(window, &sx, &sy);
  int fw = 0, fh = 0, ww = 0, wh = 0;
  glfwGetFramebufferSize(window, &fw, &fh);
  glfwGetWindowSize(window, &ww, &wh);
  const float fb_ratio = ww > 0 && fw > 0 ? float(fw) / ww : 1.0f;
  ui_scale_ = std::clamp(sx / fb_ratio, 1.0f, 4.0f);
  ImGui::GetStyle().ScaleAllSizes(ui_scale_);
  io.FontGlobalScale = ui_scale_;
  install_redraw_callbacks(window);
  g_redraw = 3;
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  // Tab with no widget active is the viewer's (hide or show the panel):
  // ImGui would take it to put the first text field of the panel in edit
  // mode. Its backend's callback calls the one installed above, which
  // queues the press for the shortcuts; here only a lone Tab skips ImGui.
  glfwSetKeyCallback(window, [](GLFWwindow* win, int key, int scancode, int action, int mods) {
    if (key == GLFW_KEY_TAB && !ImGui::IsAnyItemActive()) {
      if (action == GLFW_PRESS) g_key_presses.push_back({key, mods, false});
      mark_redraw();
      return;
    }
    ImGui_ImplGlfw_KeyCallback(win, key, scancode, action, mods);
  });
  ImGui_ImplOpenGL3_Init("#version 330");
}

ImGuiSession::~ImGuiSession() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

FrameSize frame_size(GLFWwindow* window) {
  FrameSize f;
  glfwGetFramebufferSize(window, &f.fb_w, &f.fb_h);
  int ww = 0, wh = 0;
  glfwGetWindowSize(window, &ww, &wh);
  f.win_w = float(ww);
  f.win_h = float(wh);
  f.fb_per_win = ww > 0 ? float(f.fb_w) / ww : 1.0f;
  return f;
}


}  // namespace whisker
