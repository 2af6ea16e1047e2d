// End to end: the command line's rules and messages (how many samples a
// headless render takes, option errors, progress in a log, float units and
// what an image records about its render).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "io/image_io.h"
#include "scene/scene_io.h"
#include "scene/settings_json.h"
#include "sanitized.h"

namespace fs = std::filesystem;
using namespace whisker;

namespace {

// A value of `f` other than its default, as the command line writes it.
struct OtherValue {
  const SettingField& f;
  std::string operator()(bool RenderSettings::*m) const { return RenderSettings{}.*m ? "off" : "on"; }
  std::string operator()(int RenderSettings::*) const { return std::to_string(int(f.lo) + 1); }
  std::string operator()(std::uint64_t RenderSettings::*) const { return std::to_string(int(f.lo) + 1); }
  template <NamedEnum E>
  std::string operator()(E RenderSettings::*m) const {
    for (const auto& n : enum_names(E{}))
      if (n.value != RenderSettings{}.*m) return n.name;
    return "";
  }
  std::string operator()(std::vector<int> RenderSettings::*) const { return "3,2"; }
  std::string operator()(vec3 RenderSettings::*) const { return f.example; }
};

std::string other_value(const SettingField& f) { return std::visit(OtherValue{f}, f.member); }

struct Outcome {
  int code = -1;
  std::string out, err;  // stdout, stderr
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class CommandLineE2E : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("whisker-cli-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string f(const std::string& name) const { return (dir_ / name).string(); }

  // The binary with `args`; stdout and stderr apart (stderr is a file, not
  // a terminal). `env` goes before it (e.g. "env -u WHISKER_ASSETS").
  Outcome run(const std::string& args, const std::string& env = "") const {
    const std::string cmd = env + " '" + WHISKER_BIN + "' " + args + " >'" + f("out.txt") +
                            "' 2>'" + f("err.txt") + "'";
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(f("out.txt")),
            slurp(f("err.txt"))};
  }

  // A small scene: a ball on a floor, `w` x `h` pixels, the given settings.
  std::string scene(int w, int h, int spp, int target_spp) const {
    std::ofstream(f("small.json"))
        << R"({"name": "small", "camera": {"position": [0, 0, 55], "look_at": [0, 0, 0], )"
        << "\"width\": " << w << ", \"height\": " << h << R"(},
 "light": {"position": [-10, 20, 40], "intensity": 2e10},
 "settings": {"spp": )" << spp << ", \"target_spp\": " << target_spp << R"(},
 "spheres": [{"center": [0, -1000, 0], "radius": 990, "material": {"type": "diffuse", "albedo": [0, 0, 1]}},
             {"center": [0, 0, 0], "radius": 10, "material": {"type": "diffuse", "albedo": [1, 1, 1]}}]})";
    return f("small.json");
  }

  nlohmann::json stats() const { return nlohmann::json::parse(slurp(f("s.json"))); }

  fs::path dir_;
};

}  // namespace

TEST_F(CommandLineE2E, HeadlessTakesFramesElseTheScenesTarget) {
  // Anti-aliasing on: a random estimate, so the passes are not all the same.
  const std::string base = "--headless --quiet --scene " + scene(16, 16, 2, 6) + " --aa on --stats " +
                           f("s.json") + " ";
  struct Case {
    std::string args;
    int spp, passes;
  };
  const Case cases[] = {
      {"", 6, 3},                      // the scene's target_spp: 3 passes of its spp 2
      {"--frames 1", 2, 1},            // --frames N: N passes of --spp
      {"--frames 2 --spp 3", 6, 2},
      {"--target-spp 4", 4, 2},        // --target-spp is honoured
      {"--target-spp 5", 5, 3},        // the last pass is cut to the target
  };
  for (const Case& c : cases) {
    const Outcome r = run(base + c.args);
    ASSERT_EQ(r.code, 0) << c.args << "\n" << r.err;
    EXPECT_EQ(stats()["spp"], c.spp) << c.args;
    EXPECT_EQ(stats()["passes"], c.passes) << c.args;
  }
  // A scene without a target (0 = never stop) renders one pass.
  const std::string endless = "--headless --quiet --scene " + scene(16, 16, 3, 0) + " --stats " +
                              f("s.json");
  ASSERT_EQ(run(endless).code, 0);
  EXPECT_EQ(stats()["spp"], 3);
  // A deterministic estimate (no indirect light, no anti-aliasing, no
  // Fresnel choice) without --frames or --target-spp: one pass, said exact;
  // --frames still gives its passes.
  const std::string exact = "--headless --quiet --scene " + scene(16, 16, 2, 6) + " --stats " +
                            f("s.json");
  const Outcome one = run(exact);
  ASSERT_EQ(one.code, 0) << one.err;
  EXPECT_EQ(stats()["passes"], 1);
  EXPECT_EQ(stats()["spp"], 2);
  EXPECT_EQ(stats()["exact"], true);
  // The summary line says so and names every output, --stats included.
  EXPECT_NE(one.out.find("exact"), std::string::npos) << one.out;
  EXPECT_NE(one.out.find("-> " + f("s.json")), std::string::npos) << one.out;
  ASSERT_EQ(run(exact + " --frames 3").code, 0);
  EXPECT_EQ(stats()["passes"], 3);
  EXPECT_EQ(stats()["exact"], true);
  // Both set where the render stops: refused, never one silently ignored.
  const Outcome both = run(base + "--frames 2 --target-spp 4");
  EXPECT_EQ(both.code, 2);
  EXPECT_NE(both.err.find("--frames 2 and --target-spp 4"), std::string::npos) << both.err;
}

TEST_F(CommandLineE2E, OptionErrorsAreOneLineNamingTheOption) {
  const std::string out = " --out " + f("x.png");
  const std::string small = " --scene " + scene(8, 8, 1, 1);
  struct Case {
    std::string args, expect;
  };
  const Case cases[] = {
      {"-headless --scene cat" + out, "-headless: options start with two dashes; did you mean --headless?"},
      {"--headless --frames abc" + small + out, "--frames abc: expected an integer"},
      {"--headless --frames 0" + small + out, "--frames 0: must be in [1, 16777216]"},
      {"--headless --intensity -5" + small + out, "--intensity -5: must be in [0, 1e30]"},
      {"--headless --intensity nan" + small + out, "--intensity nan: expected a number"},
      {"--headless --threads 2x" + small + out, "--threads 2x: expected an integer"},
      {"--headless --scene cat.json" + out, "did you mean --scene cat?"},
      {"--headless --scene cta" + out, "bundled scenes: antialiased-ball, cat, cat-brute,"},
      {"--headless --scene cat --mesh " + f("nothere.obj") + out, "--mesh " + f("nothere.obj") + ": no such file"},
      {"--headless --bogus" + small + out, "unknown option --bogus (see --help)"},
      {"--headless --frams 2" + small + out, "unknown option --frams; did you mean --frames?"},
      {"--headless" + small + out + " --frames", "--frames: needs a value"},
      {"--headless stray" + small + out, "unexpected argument stray"},
      {"--headless --float-units nits" + small + out, "--float-units nits: expected scene or display"},
      {"--headless --float-units Display" + small + out, "--float-units Display: expected scene or display"},
      {"--headless --float-units display" + small + out, "--float-units display is for --headless --out-float"},
      {"--headless" + small + " --out " + f("x.jpg"), "must end in .png"},
      {"--headless --light 1e8,0,0" + small + out, "--light 1e8,0,0: coordinates must be in [-1e7, 1e7]"},
      {"--headless --light nan,0,0" + small + out, "--light nan,0,0: expected three finite numbers"},
      {"merge --out " + f("m.exr"), "merge: no parts given; usage: whisker merge PART.exr"},
      {"merge", "merge: no parts given"},
      {"merge " + f("a.exr") + " --bogus", "unknown option --bogus (see --help)"},
      {"merge " + f("a.exr") + " --out", "--out: needs a value"},
      {"--features" + small + out, "--features needs --headless"},
      {"merge " + f("a.exr") + " --out-denoised " + f("d.jpg"), "merge --out-denoised " + f("d.jpg") +
                                                                  ": must end in .png, .pfm or .exr"},
      {"merge " + f("a.exr") + " --out-denoised " + f("a.exr"), "--out-denoised " + f("a.exr") +
                                                                  ": is one of the parts"},
      {"merge " + f("a.exr") + " --out-denoised ''", "merge --out-denoised: needs a value, got \"\""},
  };
  for (const Case& c : cases) {
    const Outcome r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    // One line, "whisker: " first, and nothing else on either stream.
    EXPECT_EQ(r.err.rfind("whisker: ", 0), 0u) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(r.out, "") << c.args;
    EXPECT_EQ(r.err.find("or pass --mesh"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(f("x.png")));
}

TEST_F(CommandLineE2E, HelpSaysWhatFramesDoes) {
  const Outcome r = run("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("render N passes, then keep the window open; with --screenshot, save it "
                       "and exit"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("default: the scene's target_spp"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--float-units"), std::string::npos) << r.out;
}

TEST_F(CommandLineE2E, ExtensionsInAnyCase) {
  const Outcome r = run("--headless --quiet --scene " + scene(8, 8, 1, 1) + " --out " + f("a.PNG") +
                    " --out-float " + f("a.PFM"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(f("a.PNG")).substr(1, 3), "PNG");
  EXPECT_EQ(read_pfm(f("a.PFM")).width, 8);
}

TEST_F(CommandLineE2E, ProgressLinesWhenStderrIsALog) {
  // stderr is a file: plain lines every --progress seconds, each with the
  // samples done of the target, the time elapsed and the time left. The
  // render must outlast the rate's first 0.2 s by a few lines (about 1 s
  // in Release; at 128 x 128 it once finished in 0.25 s, with no rate yet).
  // Under a sanitizer a fifth of the frames lasts as long.
  const int frames = release_or_sanitized(30, 6);
  const Outcome r = run("--headless --scene " + scene(256, 256, 16, 1) + " --frames " +
                        std::to_string(frames) + " --progress 0.1 --out " + f("a.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.err);
  std::string line;
  const std::string target = std::to_string(16 * frames) + " spp (";
  int n = 0, with_eta = 0;
  while (std::getline(lines, line)) {
    EXPECT_EQ(line.find('\r'), std::string::npos) << line;
    EXPECT_EQ(line.rfind("small: ", 0), 0u) << line;
    EXPECT_NE(line.find('/' + target), std::string::npos) << line;
    EXPECT_NE(line.find(" elapsed, eta "), std::string::npos) << line;
    with_eta += line.find("eta --") == std::string::npos;
    ++n;
  }
  EXPECT_GE(n, 2) << r.err;
  EXPECT_GE(with_eta, 1) << r.err;  // a rate was measured
  EXPECT_NE(r.out.find("samples/s"), std::string::npos) << r.out;
  // --quiet: nothing on stderr.
  EXPECT_EQ(run("--headless --quiet --scene " + scene(64, 64, 1, 1) + " --frames 2 --out " +
                f("b.png"))
                .err,
            "");
}

TEST_F(CommandLineE2E, DisplayReferredFloatsAndWhatTheFileRecords) {
  const std::string base =
      "--headless --quiet --scene " + scene(16, 16, 1, 2) + " --seed 7 --aa on --stats " + f("s.json");
  ASSERT_EQ(run(base + " --out-float " + f("scene.pfm")).code, 0);
  EXPECT_EQ(stats()["float_units"], "scene");
  const Outcome r = run(base + " --out-float " + f("display.pfm") + " --float-units display");
  ASSERT_EQ(r.code, 0) << r.err;
  const Image a = read_pfm(f("scene.pfm")), b = read_pfm(f("display.pfm"));
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  const double white = std::pow(255.0, 2.2);
  double brightest = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    EXPECT_NEAR(b.rgb[i], a.rgb[i] / white, 1e-6 * (1 + a.rgb[i] / white)) << i;
    brightest = std::max(brightest, double(b.rgb[i]));
  }
  EXPECT_GT(brightest, 0.1);  // a lit ball, not scaled to nothing
  const auto s = stats();
  EXPECT_EQ(s["float_units"], "display");
  EXPECT_EQ(s["camera"]["position"], nlohmann::json({0.0, 0.0, 55.0}));
  EXPECT_EQ(s["camera"]["width"], 16);
  EXPECT_EQ(s["settings"]["seed"], 7);
  EXPECT_GT(s["samples_per_s"].get<double>(), 0.0);
  if (!have_exr()) GTEST_SKIP() << "built without OpenEXR";
  ASSERT_EQ(run(base + " --out-float " + f("a.exr") + " --float-units display").code, 0);
  const std::string exr = slurp(f("a.exr"));
  for (const char* text :
       {"whisker.spp", "whisker.seed", "whisker.seconds", "whisker.settings", "whisker.scene",
        "\"position\":[0.0,0.0,55.0]", "display: 1.0 = 255^2.2", "\"target_spp\":2"})
    EXPECT_NE(exr.find(text), std::string::npos) << text;
}

TEST_F(CommandLineE2E, DefaultSceneRendersFromTheSourceTreesAssets) {
  // The cat, as a fresh clone has it: no WHISKER_ASSETS, run from elsewhere.
  const Outcome r = run("--headless --quiet --target-spp 1 --out-float " + f("cat.pfm"),
                    "cd '" + dir_.string() + "' && env -u WHISKER_ASSETS -u WHISKER_SCENES");
  ASSERT_EQ(r.code, 0) << r.err;
  const Image img = read_pfm(f("cat.pfm"));
  ASSERT_EQ(img.width, 512);
  // The middle of the image is the cat, lit.
  const std::size_t c = (std::size_t(256) * 512 + 256) * 3;
  EXPECT_GT(img.rgb[c] + img.rgb[c + 1] + img.rgb[c + 2], 0.0f);
}

#ifdef WHISKER_HAVE_VIEWER
TEST_F(CommandLineE2E, NoDisplayHintIsACommandThatWorks) {
  // The viewer without a display exits 3 and suggests a headless command;
  // that command, run as printed (on a small scene), must render.
  const std::string sc = scene(8, 8, 1, 1);
  const Outcome r = run("--scene " + sc, "env -u DISPLAY -u WAYLAND_DISPLAY");
  ASSERT_EQ(r.code, 3) << r.err;
  const std::string head = "  whisker ";
  const std::size_t at = r.err.find(head);
  ASSERT_NE(at, std::string::npos) << r.err;
  std::string args = r.err.substr(at + head.size());
  args = args.substr(0, args.find('\n'));
  EXPECT_NE(args.find("--headless"), std::string::npos) << args;
  const std::size_t out = args.find("image.png");
  ASSERT_NE(out, std::string::npos) << args;
  args.replace(out, 9, f("hint.png"));
  const Outcome h = run(args + " --quiet");
  EXPECT_EQ(h.code, 0) << args << "\n" << h.err;
  EXPECT_EQ(slurp(f("hint.png")).substr(1, 3), "PNG");
}
#endif

TEST_F(CommandLineE2E, ObjFileFitsTheFacesNotAStrayVertex) {
  // A valid OBJ with one vertex no face uses, far off (1e30: the fit of the
  // whole box left the triangle no area and aborted with exit 134; 1e7: it
  // shrank the triangle out of sight): fitted as the triangle alone.
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  std::ofstream(f("tri.obj")) << tri << "f 1 2 3\n";
  std::ofstream(f("far30.obj")) << tri << "v 1e30 1e30 1e30\nf 1 2 3\n";
  std::ofstream(f("far7.obj")) << tri << "v 1e7 1e7 1e7\nf 1 2 3\n";
  // Direct light only: a quick render, the same every run.
  const std::string quick = " --frames 1 --indirect off --connect off --aa off --quiet --out ";
  ASSERT_EQ(run("--headless " + f("tri.obj") + quick + f("tri.png")).code, 0);
  for (const std::string name : {"far30", "far7"}) {
    const Outcome r = run("--headless " + f(name + ".obj") + quick + f(name + ".png"));
    ASSERT_EQ(r.code, 0) << name << ": " << r.err;
    EXPECT_EQ(slurp(f(name + ".png")), slurp(f("tri.png"))) << name << " is not the triangle fitted";
  }
  // The viewer's path (the desktop entry's `whisker FILE`) loads the same
  // way: without a display it gets as far as the window (exit 3).
  const Outcome v = run(f("far30.obj"), "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_EQ(v.code, 3) << v.err;
  // Nothing with an area: one line naming the file, exit 2, never an abort.
  std::ofstream(f("line.obj")) << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
  for (const std::string& args : {"--headless " + f("line.obj") + quick + f("l.png"), f("line.obj")}) {
    const Outcome r = run(args, "env -u DISPLAY -u WAYLAND_DISPLAY");
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(r.err, "whisker: " + f("line.obj") + ": no triangles with non-zero area\n") << args;
  }
}

TEST_F(CommandLineE2E, MeshPathsAreNamedAsGiven) {
  // FILE is named alone (no --mesh was typed), --mesh PATH with the option;
  // a folder is there, so "not a regular file", not "no such file".
  fs::create_directories(f("dir.obj"));
  const std::string out = " --out " + f("x.png");
  const std::pair<std::string, std::string> cases[] = {
      {"--headless " + f("dir.obj") + out, f("dir.obj") + ": not a regular file (a folder)"},
      {f("dir.obj"), f("dir.obj") + ": not a regular file (a folder)"},
      {"--headless " + f("none.obj") + out, f("none.obj") + ": no such file"},
      {"--headless --scene cat --mesh " + f("dir.obj") + out,
       "--mesh " + f("dir.obj") + ": not a regular file (a folder)"},
  };
  for (const auto& [args, expect] : cases) {
    const Outcome r = run(args, "env -u DISPLAY -u WAYLAND_DISPLAY");
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(r.err, "whisker: " + expect + "\n") << args;
  }
}

#ifdef WHISKER_HAVE_VIEWER
TEST_F(CommandLineE2E, NoDisplayHintKeepsTheMesh) {
  // `whisker FILE.obj` without a display: the command suggested shows the
  // same mesh (FILE, quoted for the shell), not the bare cat scene.
  std::ofstream(f("my tri.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string nodisplay = "env -u DISPLAY -u WAYLAND_DISPLAY";
  const Outcome r = run("'" + f("my tri.obj") + "'", nodisplay);
  ASSERT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("\n  whisker --headless '" + f("my tri.obj") +
                       "' --target-spp 32 --out image.png\n"),
            std::string::npos)
      << r.err;
  // --scene S --mesh M: both, and the command renders that scene and mesh.
  std::ofstream(f("meshy.json"))
      << R"({"name": "meshy", "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "width": 8, "height": 8},
 "light": {"position": [0, 0, 10]}, "settings": {"target_spp": 1},
 "meshes": [{"path": "nowhere.obj"}]})";
  const Outcome m = run("--scene " + f("meshy.json") + " --mesh '" + f("my tri.obj") + "'", nodisplay);
  ASSERT_EQ(m.code, 3) << m.err;
  const std::string head = "\n  whisker ";
  const std::size_t at = m.err.find(head);
  ASSERT_NE(at, std::string::npos) << m.err;
  std::string args = m.err.substr(at + head.size());
  args = args.substr(0, args.find('\n'));
  EXPECT_EQ(args, "--headless --scene " + f("meshy.json") + " --mesh '" + f("my tri.obj") +
                      "' --target-spp 32 --out image.png");
  args.replace(args.find("image.png"), 9, f("hint.png"));
  const Outcome h = run(args + " --quiet");
  EXPECT_EQ(h.code, 0) << args << "\n" << h.err;
  EXPECT_EQ(slurp(f("hint.png")).substr(1, 3), "PNG");
}
#endif

TEST_F(CommandLineE2E, OutputFolderProblemsKeepTheirReason) {
  const std::string small = "--headless --quiet --frames 1 --scene " + scene(8, 8, 1, 1) + " --out ";
  // A file where the folder should be: not a folder, not "does not exist".
  std::ofstream(f("afile")) << "x";
  for (const std::string& out : {f("afile/x.png"), f("afile/sub/x.png")}) {
    const Outcome r = run(small + out);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.err, "whisker: --out " + out + ": " + f("afile") + " is not a folder\n");
  }
  // Paths over PATH_MAX (4096 bytes): one line, the path shortened in its
  // middle, and the reason kept. One whose folder is missing; one whose
  // folder exists (just under PATH_MAX) and whose name takes it over.
  std::string deep = dir_.string();
  while (deep.size() + 201 < 4096) deep += "/" + std::string(200, 'd');
  fs::create_directories(deep);
  const std::string missing = deep + "/" + std::string(200, 'm') + "/" + std::string(200, 'n') + "/x.png";
  const std::string over = deep + "/" + std::string(250, 'n') + ".png";
  for (const std::string& out : {missing, over}) {
    ASSERT_GT(out.size(), 4096u);
    const Outcome r = run(small + out);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("whisker: --out " + out.substr(0, 100) + "...", 0), 0u) << r.err;
    EXPECT_LT(r.err.size(), 1000u) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
    const std::string reason = "File name too long\n";
    ASSERT_GE(r.err.size(), reason.size());
    EXPECT_EQ(r.err.substr(r.err.size() - reason.size()), reason) << r.err;
  }
}

// The settings table drives the command line, the scene file, the stats, the
// EXR header and the man page: every row, given a value other than its
// default on the command line, comes back with that value from the stats
// and from a scene file written and read again, and is named in --help,
// the EXR header and the man page.
TEST_F(CommandLineE2E, EverySettingOfTheTableWalksThroughEveryOutput) {
  std::string args = "--headless --quiet --scene " + scene(8, 8, 1, 1) + " --stats " + f("s.json");
  for (const SettingField& row : setting_fields()) {
    ASSERT_NE(other_value(row), value_text(row, RenderSettings{})) << row.key;
    args += std::string(" ") + row.option + " " + other_value(row);
  }
  const bool exr = have_exr();
  const Outcome r = run(args + (exr ? " --out-float " + f("a.exr") : std::string()));
  ASSERT_EQ(r.code, 0) << args << "\n" << r.err;
  const nlohmann::json given = stats()["settings"];
  const Scene read = parse_scene(nlohmann::json{{"settings", given}}.dump(), "s.json");
  const Scene again =
      parse_scene(nlohmann::json{{"settings", settings_to_json(read.settings)}}.dump(), "t.json");
  const std::string help = run("--help").out, exr_text = exr ? slurp(f("a.exr")) : "";
  for (const SettingField& row : setting_fields()) {
    EXPECT_EQ(value_text(row, read.settings), other_value(row)) << row.key;
    EXPECT_EQ(value_text(row, again.settings), other_value(row)) << row.key;
    EXPECT_NE(help.find(std::string(row.option) + " " + value_syntax(row)), std::string::npos)
        << row.option;
    if (exr) {
      EXPECT_NE(exr_text.find("\"" + std::string(row.key) + "\":"), std::string::npos) << row.key;
    }
    // A boolean is a word --edit-toggle takes: with --headless the refusal
    // is that the script needs the viewer, not the word.
    if (std::holds_alternative<bool RenderSettings::*>(row.member)) {
      EXPECT_NE(run(std::string("--headless --edit-toggle ") + row.key).err.find("needs the viewer"),
                std::string::npos)
          << row.key;
    }
  }
}

// The built man page's settings part is what `whisker --man-settings` writes
// from the table (the build puts it there with scripts/update_man.sh): a row
// missing from the page, or written without its values, fails here.
TEST_F(CommandLineE2E, ManPageListsEverySettingWithItsValues) {
  const Outcome r = run("--man-settings");
  ASSERT_EQ(r.code, 0) << r.err;
  // The page as built and installed (cmake/install.cmake writes the table in).
  const std::string page = slurp(fs::path(WHISKER_MAN_PAGE));
  const std::string begin = "edit the table, not these lines.\n", end = ".\\\" END SETTINGS";
  const std::size_t a = page.find(begin), b = page.find(end);
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  EXPECT_EQ(page.substr(a + begin.size(), b - a - begin.size()), r.out)
      << "the built man page differs from the settings table";
  auto roff = [](std::string t) {
    for (std::size_t k = 0; (k = t.find('-', k)) != std::string::npos; k += 2) t.insert(k, "\\");
    return t;
  };
  for (const SettingField& row : setting_fields())
    EXPECT_NE(r.out.find(".BI " + roff(row.option) + " \" " + roff(value_syntax(row)) + "\""),
              std::string::npos)
        << row.option;
}
