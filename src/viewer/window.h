// The window's resources, each released by its destructor in the reverse
// order of their creation: GLFW itself, the window with its OpenGL 3.3
// context, and Dear ImGui with its GLFW and OpenGL backends.
#pragma once

#include <string>
#include <vector>

struct GLFWwindow;

namespace whisker {

// The window's size this frame: framebuffer pixels and window units.
struct FrameSize {
  int fb_w = 0, fb_h = 0;
  float win_w = 0.0f, win_h = 0.0f;
  float fb_per_win = 1.0f;  // framebuffer pixels per window unit
};

FrameSize frame_size(GLFWwindow* window);

// glfwInit (with an error callback that keeps the last message) and
// glfwTerminate.
class GlfwSession {
 public:
  GlfwSession();
  ~GlfwSession();
  GlfwSession(const GlfwSession&) = delete;
  GlfwSession& operator=(const GlfwSession&) = delete;

  bool ok() const { return ok_; }

 private:
  bool ok_ = false;
};

// The last GLFW error, "<text> (GLFW error <code>)", for messages.
const std::string& last_glfw_error();

// The window size in logical units: the one asked for (0 = an image of
// image_w x image_h beside a panel of `panel_width`, at least 800 high),
// never larger than the primary monitor. Needs GLFW.
void initial_window_size(int image_w, int image_h, int asked_w, int asked_h, float panel_width,
                         int& width, int& height);

// A window with a current OpenGL 3.3 core context and its functions loaded
// (glad); vsync on.
class Window {
 public:
  Window(int width, int height, const char* title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  // Empty if the window is usable, else the one-line reason.
  const std::string& error() const { return error_; }
  GLFWwindow* handle() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
  std::string error_;
};

// The ImGui context (no .ini file, dark style, scaled to the window's content
// scale), the redraw callbacks and the GLFW and OpenGL 3 backends.
class ImGuiSession {
 public:
  explicit ImGuiSession(GLFWwindow* window);
  ~ImGuiSession();
  ImGuiSession(const ImGuiSession&) = delete;
  ImGuiSession& operator=(const ImGuiSession&) = delete;

  // Panel sizes are multiplied by this (1 to 4).
  float ui_scale() const { return ui_scale_; }

 private:
  float ui_scale_ = 1.0f;
};

// Input (or a window event) asks for a few frames to be drawn so ImGui can
// settle; the loop takes one of them per drawn frame.
bool redraw_pending();
void request_redraw();  // as input does
// The file dropped on the window since the last call ("" if none).
std::string take_dropped_file();

// A key pressed (or repeating) in the window, from GLFW's key callback.
struct KeyPress {
  int key = 0, mods = 0;
  bool repeat = false;
};
// The key presses since the last call, in order: none is lost when a key
// goes down and up between two frames.
std::vector<KeyPress> take_key_presses();
// Puts presses back in front of the queue, for the next frame.
void put_back_key_presses(const std::vector<KeyPress>& keys);
void take_redraw();
// Where the pointer was (window units) when mouse button b last went down,
// read in GLFW's press event.
void press_position(int b, float& x, float& y);

}  // namespace whisker
