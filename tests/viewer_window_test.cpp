// The real `whisker` window under Xvfb (Mesa's software OpenGL): what it
// shows must be the headless render of the same settings, pixel for pixel up
// to the one-level tolerance explained in compare_render_area().
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

#include <nlohmann/json.hpp>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb_image.h>
#pragma GCC diagnostic pop

namespace fs = std::filesystem;

namespace {

const fs::path kOut = fs::path(VIEWER_TEST_OUT);

int run(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool have_xvfb() { return run("command -v xvfb-run >/dev/null 2>&1") == 0; }

// The viewer in a virtual screen with Mesa's software renderer.
int run_viewer(const std::string& args, const std::string& log,
               const std::string& screen = "1280x800x24") {
  return run("xvfb-run -a -s '-screen 0 " + screen + "' env LIBGL_ALWAYS_SOFTWARE=1 '" +
             std::string(WHISKER_BIN) + "' " + args + " >'" + log + "' 2>&1");
}

int run_headless(const std::string& args, const std::string& log) {
  return run("'" + std::string(WHISKER_BIN) + "' --headless --quiet " + args + " >'" +
             log + "' 2>&1");
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Rgb8 {
  int w = 0, h = 0;
  std::vector<unsigned char> px;
  const unsigned char* at(int x, int y) const { return &px[(std::size_t(y) * w + x) * 3]; }
};

Rgb8 load_png(const fs::path& p) {
  Rgb8 img;
  int n = 0;
  unsigned char* data = stbi_load(p.c_str(), &img.w, &img.h, &n, 3);
  if (data) {
    img.px.assign(data, data + std::size_t(img.w) * img.h * 3);
    stbi_image_free(data);
  }
  return img;
}

struct Rect {
  int x, y, w, h;
};

Rect render_rect(const nlohmann::json& j) {
  const auto& r = j.at("render_rect");
  return {r[0].get<int>(), r[1].get<int>(), r[2].get<int>(), r[3].get<int>()};
}

struct Diff {
  int max = 0;          // largest channel difference (8-bit levels)
  std::size_t off = 0;  // channels that differ at all
  std::size_t channels = 0;
};

// Both paths map the same float sums with min(255, L^(1/2.2)) truncated to an
// integer: the PNG writer in C++ float, the window's shader in GLSL float
// (llvmpipe's pow). Their last-bit differences can move a value sitting on an
// integer boundary by one level, so one level is allowed on at most 1e-4 of
// the channels (measured: 1 to 5 of 786432) and nothing more; a leaked
// sample, an off-by-one row or the wrong exposure moves far more, by more.
Diff compare_render_area(const Rgb8& shot, const Rect& r, const Rgb8& ref) {
  Diff d;
  for (int y = 0; y < ref.h; ++y)
    for (int x = 0; x < ref.w; ++x)
      for (int c = 0; c < 3; ++c) {
        const int a = shot.at(r.x + x, r.y + y)[c], b = ref.at(x, y)[c];
        const int e = std::abs(a - b);
        d.max = std::max(d.max, e);
        d.off += e != 0;
        ++d.channels;
      }
  return d;
}

// Runs the viewer and the headless mode with the same settings and checks the
// screenshot's render area against the headless PNG.
void expect_window_matches_headless(const std::string& name, const std::string& viewer_args,
                                    const std::string& headless_args, Rgb8* shot_out = nullptr,
                                    nlohmann::json* summary_out = nullptr,
                                    const std::string& headless_out = "--out") {
  fs::create_directories(kOut);
  const fs::path shot = kOut / (name + "-window.png");
  const fs::path ref = kOut / (name + "-headless.png");
  fs::remove(shot);
  fs::remove(ref);
  ASSERT_EQ(run_viewer(viewer_args + " --screenshot '" + shot.string() + "'",
                       (kOut / (name + "-window.log")).string()),
            0)
      << slurp(kOut / (name + "-window.log"));
  ASSERT_EQ(run_headless(headless_args + " " + headless_out + " '" + ref.string() + "'",
                         (kOut / (name + "-headless.log")).string()),
            0)
      << slurp(kOut / (name + "-headless.log"));

  const nlohmann::json summary = nlohmann::json::parse(slurp(shot.string() + ".json"));
  const Rgb8 window = load_png(shot), headless = load_png(ref);
  ASSERT_GT(window.w, 0) << shot;
  ASSERT_GT(headless.w, 0) << ref;
  EXPECT_EQ(window.w, summary["framebuffer"][0].get<int>());
  EXPECT_EQ(window.h, summary["framebuffer"][1].get<int>());
  const Rect r = render_rect(summary);
  // Shown 1:1 so the comparison is per pixel.
  ASSERT_EQ(r.w, headless.w);
  ASSERT_EQ(r.h, headless.h);
  ASSERT_LE(r.x + r.w, window.w);
  ASSERT_LE(r.y + r.h, window.h);

  const Diff d = compare_render_area(window, r, headless);
  std::printf("%s: largest difference %d level(s), %zu of %zu channels differ\n",
              name.c_str(), d.max, d.off, d.channels);
  EXPECT_LE(d.max, 1) << name;
  EXPECT_LT(double(d.off) / d.channels, 1e-4) << name << ": " << d.off << " channels differ";
  if (shot_out) *shot_out = window;
  if (summary_out) *summary_out = summary;
}

class ViewerWindow : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not installed";
  }
};

}  // namespace

// One deterministic pass: the render area is the headless image, and the
// panel is drawn beside it.
TEST_F(ViewerWindow, ScreenshotShowsRenderAndPanel) {
  Rgb8 shot;
  nlohmann::json summary;
  expect_window_matches_headless("three-balls", "--scene three-balls --frames 1",
                                 "--scene three-balls --frames 1", &shot, &summary);
  if (HasFatalFailure()) return;
  EXPECT_EQ(summary["spp"].get<int>(), 1);
  const Rect r = render_rect(summary);

  // Not blank: the room's walls and balls give many distinct colours.
  std::vector<bool> seen(1 << 15);
  std::size_t distinct = 0;
  for (int y = r.y; y < r.y + r.h; ++y)
    for (int x = r.x; x < r.x + r.w; ++x) {
      const unsigned char* p = shot.at(x, y);
      const int key = (p[0] >> 3) << 10 | (p[1] >> 3) << 5 | (p[2] >> 3);
      if (!seen[key]) seen[key] = true, ++distinct;
    }
  EXPECT_GT(distinct, 50u);

  // The panel, right of the render area: ImGui's light text and its blue
  // widgets (frames, buttons, headers of the dark style) are there.
  std::size_t text = 0, widgets = 0, panel = 0;
  for (int y = 0; y < shot.h; ++y)
    for (int x = r.x + r.w + 4; x < shot.w; ++x) {
      const unsigned char* p = shot.at(x, y);
      ++panel;
      if (p[0] > 180 && p[1] > 180 && p[2] > 180) ++text;
      if (p[2] > 50 && p[2] > p[0] + 25) ++widgets;
    }
  ASSERT_GT(panel, 200u * 400u) << "no room for the panel";
  EXPECT_GT(text, 2000u) << "panel text missing";
  EXPECT_GT(widgets, 10000u) << "panel widgets missing";
}

// Stochastic sampling over several passes (indirect light, Fresnel, jitter):
// the window shows exactly the accumulated mean the headless mode writes.
TEST_F(ViewerWindow, AccumulationMatchesHeadless) {
  const std::string args =
      "--scene three-balls --indirect on --fresnel on --aa on --frames 4";
  nlohmann::json summary;
  expect_window_matches_headless("stochastic", args, args, nullptr, &summary);
  if (HasFatalFailure()) return;
  EXPECT_EQ(summary["spp"].get<int>(), 4);
  EXPECT_EQ(summary["passes"].get<int>(), 4);
}

// A light move after 3 passes: the final image equals a fresh render with the
// new light, so no sample of the old generation leaks into the new one.
TEST_F(ViewerWindow, ScriptedLightMoveRestartsCleanly) {
  const std::string common = "--scene diffuse-ball --aa on --indirect on --frames 5";
  nlohmann::json summary;
  expect_window_matches_headless("light-move",
                                 common + " --edit-after 3 --edit-light 15,25,30",
                                 common + " --light 15,25,30", nullptr, &summary);
  if (HasFatalFailure()) return;
  EXPECT_EQ(summary["generation"].get<int>(), 2) << "one edit, one restart";
  EXPECT_EQ(summary["spp"].get<int>(), 5);

  // The move must be visible, or the test above would prove nothing.
  const fs::path old_light = kOut / "light-move-old.png";
  ASSERT_EQ(run_headless(common + " --out '" + old_light.string() + "'",
                         (kOut / "light-move-old.log").string()),
            0);
  const Rgb8 a = load_png(old_light), b = load_png(kOut / "light-move-headless.png");
  ASSERT_EQ(a.px.size(), b.px.size());
  std::size_t changed = 0;
  for (std::size_t k = 0; k < a.px.size(); ++k) changed += std::abs(a.px[k] - b.px[k]) > 8;
  EXPECT_GT(changed, a.px.size() / 20);
}

// Fresnel switched where nothing is glass changes nothing the render can
// show: the accumulation carries on (one generation, every pass kept), and
// the image is the headless one with Fresnel as it was. Where there is
// glass the same switch restarts.
TEST_F(ViewerWindow, FresnelWithoutGlassRestartsNothing) {
  const std::string common = "--scene diffuse-ball --aa on --indirect on --frames 5";
  nlohmann::json summary;
  expect_window_matches_headless("fresnel-no-glass", common + " --edit-after 2 --edit-toggle fresnel",
                                 common, nullptr, &summary);
  if (HasFatalFailure()) return;
  EXPECT_EQ(summary["generation"].get<int>(), 1) << "no restart";
  EXPECT_EQ(summary["spp"].get<int>(), 5);
  const std::string glass = "--scene three-balls --aa on --frames 4";
  expect_window_matches_headless("fresnel-glass", glass + " --edit-after 2 --edit-toggle fresnel",
                                 glass + " --fresnel on", nullptr, &summary);
  if (HasFatalFailure()) return;
  EXPECT_EQ(summary["generation"].get<int>(), 2) << "with glass, Fresnel restarts";
}

// Many samples per pass (16): the window's first image of the render's own
// estimator comes after one sample and refines pass by pass (1, 2, 4, 8,
// 16), where it stood still at the quick passes' image until a whole pass of
// 16 had finished. Read from the event log of an interactive run (quick
// passes on: no screenshot).
TEST_F(ViewerWindow, ManySamplesPerPassRefineFromTheFirstSample) {
  fs::create_directories(kOut);
  const fs::path log = kOut / "growing.events";
  fs::remove(log);
  ASSERT_EQ(run_viewer("--scene three-balls --indirect on --aa on --threads 1 --spp 16 --frames 1 "
                       "--edit-log '" + log.string() + "'",
                       (kOut / "growing.log").string()),
            0);
  std::istringstream events(slurp(log));
  std::vector<int> shown;  // the own samples in the image shown, as they change
  for (std::string line; std::getline(events, line);) {
    const std::size_t at = line.find(" shown_own=");
    if (line.rfind("frame ", 0) != 0 || at == std::string::npos) continue;
    const int own = std::stoi(line.substr(at + 11));
    if (own > 0 && (shown.empty() || shown.back() != own)) shown.push_back(own);
  }
  ASSERT_FALSE(shown.empty()) << slurp(log);
  EXPECT_EQ(shown.back(), 16) << "the run ends at its 16 samples";
  EXPECT_LT(shown.front(), 16) << "the first image of the render's own waited for a whole pass";
  EXPECT_GE(shown.size(), 3u) << "the image did not refine before the first pass of 16";
}

// The light moved out of the cat's room: the panel says so (the event log
// records what it says) and the image is black; before the move, inside
// the room, it says nothing.
TEST_F(ViewerWindow, LightOutsideTheRoomIsSaid) {
  fs::create_directories(kOut);
  const fs::path log = kOut / "light-outside.events", shot = kOut / "light-outside.png";
  fs::remove(log);
  ASSERT_EQ(run_viewer("--scene cat --threads 1 --frames 3 --edit-after 1 --edit-light 1000,20,40 "
                       "--edit-log '" + log.string() + "' --screenshot '" + shot.string() + "'",
                       (kOut / "light-outside.log").string()),
            0);
  const std::string events = slurp(log);
  const std::size_t edit = events.find("edit t="), moved = events.find("gen=2");
  ASSERT_NE(moved, std::string::npos) << events;
  const std::size_t said = events.find("light-outside t=");
  ASSERT_NE(said, std::string::npos) << "the light outside the room was not said:\n" << events;
  EXPECT_GT(said, moved) << "said before the light moved";
  EXPECT_NE(events.find("text=the light", said), std::string::npos) << events;
  EXPECT_NE(edit, std::string::npos);
  const nlohmann::json summary = nlohmann::json::parse(slurp(shot.string() + ".json"));
  const Rgb8 window = load_png(shot);
  const Rect r = render_rect(summary);
  int lit = 0;
  for (int y = 0; y < r.h; ++y)
    for (int x = 0; x < r.w; ++x)
      for (int c = 0; c < 3; ++c) lit += window.at(r.x + x, r.y + y)[c] > 8;
  EXPECT_EQ(lit, 0) << "a light outside the room lit the image";
}

// The denoised view (--denoised, the panel's Denoised box): the window shows
// the headless denoised copy of the same passes (--out-denoised with the
// fast filter), pixel for pixel, and the panel says it is denoised; the raw
// window differs from it.
TEST_F(ViewerWindow, DenoisedViewIsTheHeadlessDenoisedImage) {
  Rgb8 denoised, raw;
  nlohmann::json summary;
  expect_window_matches_headless("denoised", "--scene cat --frames 2 --denoised",
                                 "--scene cat --frames 2 --denoiser fast", &denoised, &summary,
                                 "--out-denoised");
  if (HasFatalFailure()) return;
  expect_window_matches_headless("raw", "--scene cat --frames 2", "--scene cat --frames 2", &raw);
  if (HasFatalFailure()) return;
  const Rect r = render_rect(summary);
  long differ = 0;
  for (int y = 0; y < r.h; ++y)
    for (int x = 0; x < r.w; ++x)
      for (int c = 0; c < 3; ++c)
        differ += std::abs(int(denoised.at(r.x + x, r.y + y)[c]) - int(raw.at(r.x + x, r.y + y)[c])) > 8;
  EXPECT_GT(differ, long(r.w) * r.h / 20) << "the denoised window looks like the raw one";
}

// The default scene (the cat, indirect + AA) after two passes.
TEST_F(ViewerWindow, CatMatchesHeadless) {
  expect_window_matches_headless("cat", "--frames 2", "--scene cat --frames 2");
}

// On a screen too small for the image beside the panel, the window fits the
// screen (640x480), the panel narrows to its narrowest (280) and the image
// is scaled down, keeping its aspect, beside it (viewer/layout.h).
TEST_F(ViewerWindow, SmallScreenScalesImageDown) {
  fs::create_directories(kOut);
  const fs::path shot = kOut / "small-window.png", ref = kOut / "small-headless.png";
  ASSERT_EQ(run_viewer("--scene three-balls --frames 1 --screenshot '" + shot.string() + "'",
                       (kOut / "small-window.log").string(), "640x480x24"),
            0)
      << slurp(kOut / "small-window.log");
  ASSERT_EQ(run_headless("--scene three-balls --frames 1 --out '" + ref.string() + "'",
                         (kOut / "small-headless.log").string()),
            0);
  const nlohmann::json summary = nlohmann::json::parse(slurp(shot.string() + ".json"));
  const Rgb8 window = load_png(shot), headless = load_png(ref);
  ASSERT_EQ(window.w, summary["framebuffer"][0].get<int>());
  EXPECT_LE(window.w, 640);
  EXPECT_LE(window.h, 480);
  const Rect r = render_rect(summary);
  EXPECT_LT(r.w, 512);
  EXPECT_EQ(r.w, r.h);
  EXPECT_EQ(r.w, window.w - 280) << "the image takes all the narrowest panel leaves";
  EXPECT_GE(r.x, 0);
  EXPECT_LE(r.x + r.w, window.w - 280) << "image under the panel";

  // Scaled, so compare region averages: each quarter of the image.
  for (int q = 0; q < 4; ++q) {
    const int qx = q % 2, qy = q / 2;
    double a[3] = {}, b[3] = {};
    for (int y = 0; y < r.h / 2; ++y)
      for (int x = 0; x < r.w / 2; ++x)
        for (int c = 0; c < 3; ++c)
          a[c] += window.at(r.x + qx * r.w / 2 + x, r.y + qy * r.h / 2 + y)[c];
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x)
        for (int c = 0; c < 3; ++c) b[c] += headless.at(qx * 256 + x, qy * 256 + y)[c];
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(a[c] / (r.w / 2 * (r.h / 2)), b[c] / (256 * 256), 3.0)
          << "quarter " << q << " channel " << c;
  }
}

// Without a display the viewer says so, points at --headless and exits 3.
TEST(ViewerNoDisplay, ExitsWithHint) {
  fs::create_directories(kOut);
  const fs::path log = kOut / "no-display.log";
  const int code = run("env -u DISPLAY -u WAYLAND_DISPLAY '" + std::string(WHISKER_BIN) +
                       "' --scene three-balls --frames 1 >'" + log.string() + "' 2>&1");
  EXPECT_EQ(code, 3);
  EXPECT_NE(slurp(log).find("--headless"), std::string::npos) << slurp(log);
}

// A steady panel: after one pass (no error yet, no plot data) and after
// four (an error, a plot) everything below the status lines is in the same
// place, so a second quick click lands where the first look found it. Only
// the "target spp" field's digits may differ between the two.
TEST_F(ViewerWindow, PanelLayoutDoesNotMoveAsTheRenderGoesOn) {
  Rgb8 shots[2];
  Rect rect{};
  const int frames[2] = {1, 4};
  for (int k = 0; k < 2; ++k) {
    const fs::path shot = kOut / ("steady-" + std::to_string(frames[k]) + ".png");
    ASSERT_EQ(run_viewer("--scene three-balls --threads 1 --frames " + std::to_string(frames[k]) +
                             " --screenshot '" + shot.string() + "'",
                         (kOut / "steady.log").string()),
              0);
    shots[k] = load_png(shot);
    rect = render_rect(nlohmann::json::parse(slurp(shot.string() + ".json")));
  }
  ASSERT_EQ(shots[0].w, shots[1].w);
  ASSERT_EQ(shots[0].h, shots[1].h);
  // The left strip of the panel (widget frames, buttons, headers), from the
  // Pause button's row down; a tooltip under the pointer would be further right.
  const int x0 = rect.x + rect.w + 4, x1 = x0 + 70, y0 = 215;
  int rows_differ = 0;
  for (int y = y0; y < shots[0].h; ++y) {
    bool same = true;
    for (int x = x0; x < x1 && same; ++x)
      same = std::equal(shots[0].at(x, y), shots[0].at(x, y) + 3, shots[1].at(x, y));
    rows_differ += !same;
  }
  std::printf("rows that differ: %d\n", rows_differ);
  EXPECT_LE(rows_differ, 16) << "the panel moved between pass 1 and pass 4";
}
