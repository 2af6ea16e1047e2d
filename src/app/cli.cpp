#include "app/cli.h"
#include "app/open_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include <CLI/CLI.hpp>
#include <unistd.h>

#include "io/image_io.h"
#include "scene/quote.h"
#include "scene/scene_io.h"
#include "whisker_version.h"

namespace whisker {

namespace fs = std::filesystem;

namespace {

std::string number_text(double v) {
  std::ostringstream s;
  s << std::setprecision(12) << v;
  std::string t = s.str();
  if (const auto e = t.find("e+"); e != std::string::npos) t.erase(e + 1, 1);  // 1e30
  return t;
}

// A refusal of an option's value, worded in full: "--frames abc: expected
// an integer". Thrown from a check while CLI11 parses, it ends the parse as
// CLI11's own errors do, and is printed as it is (parse_failure).
class BadValue : public CLI::ParseError {
 public:
  explicit BadValue(const std::string& message)
      : CLI::ParseError("BadValue", message, kUsageError) {}
};

// A check of `option`'s value: `why` says what is wrong with a text, or "".
CLI::Validator refusing(const std::string& option,
                        std::function<std::string(const std::string&)> why) {
  return CLI::Validator(
      [option, why](std::string& text) -> std::string {
        if (const std::string w = why(text); !w.empty())
          throw BadValue(option + " " + cut_for_message(text) + ": " + w);
        return {};
      },
      "");
}

// A word of `words` (as CLI::IsMember, in Whisker's words: "expected scene
// or display").
CLI::Validator one_of(const std::string& option, std::vector<std::string> words) {
  std::string list;
  for (std::size_t i = 0; i < words.size(); ++i)
    list += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
  return refusing(option, [words, list](const std::string& t) {
    return std::find(words.begin(), words.end(), t) != words.end() ? std::string() : "expected " + list;
  });
}

// An integer option in [lo, hi], read by the one integer reader (settings.h).
CLI::Option* int_in(CLI::Option* option, long long lo, long long hi) {
  const std::string range = "[" + number_text(double(lo)) + ", " + number_text(double(hi)) + "]";
  return option
      ->check(refusing(option->get_name(),
                       [=](const std::string& text) {
                         long long v = 0;
                         return read_integer(text, lo, hi, v);
                       }))
      ->type_name("INT in " + range);
}

// What is wrong with `text` as a finite number in [lo, hi] ("" if nothing).
std::string number_problem(const std::string& text, double lo, double hi) {
  const std::string range = "[" + number_text(lo) + ", " + number_text(hi) + "]";
  double v = 0.0;
  if (!read_number(text, v)) {
    // In full a number, but past double's range (1e400): a range error.
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (!text.empty() && end == text.data() + text.size() && ec == std::errc::result_out_of_range)
      return "must be in " + range;
    return "expected a number";
  }
  return v < lo || v > hi ? "must be in " + range : std::string();
}

// A number option in [lo, hi], read by the one number reader (settings.h).
CLI::Option* number_in(CLI::Option* option, double lo, double hi) {
  const std::string range = "[" + number_text(lo) + ", " + number_text(hi) + "]";
  return option
      ->check(refusing(option->get_name(),
                       [=](const std::string& text) { return number_problem(text, lo, hi); }))
      ->type_name("NUMBER in " + range);
}

// A settings option, typed as its member: CLI11 converts the text into the
// member once a check has accepted it (enum names turned into their values
// first). Lists are read by the table's own reader.
struct SettingOption {
  CLI::App& app;
  const SettingField& f;
  RenderSettings& s;
  CLI::Option* add(CLI::Option* o) const { return o->type_name(value_syntax(f)); }
  CLI::Option* operator()(bool RenderSettings::*m) const {
    const auto on_off = [](const std::string& t) {
      return t == "on" || t == "off" ? std::string() : "expected on or off";
    };
    return add(app.add_option(f.option, s.*m, f.help)->check(refusing(f.option, on_off)));
  }
  template <class T>
    requires std::is_integral_v<T>
  CLI::Option* operator()(T RenderSettings::*m) const {
    const double hi = f.option_hi > 0 ? f.option_hi : f.hi;
    return add(int_in(app.add_option(f.option, s.*m, f.help), (long long)f.lo, (long long)hi));
  }
  template <NamedEnum E>
  CLI::Option* operator()(E RenderSettings::*m) const {
    const CLI::Validator by_name(
        [option = std::string(f.option)](std::string& text) -> std::string {
          E e{};
          if (!parse(text, e))
            throw BadValue(option + " " + cut_for_message(text) + ": expected " + name_list(e));
          text = std::to_string(int(e));
          return {};
        },
        "");
    return add(app.add_option<E, std::underlying_type_t<E>>(f.option, s.*m, f.help)->transform(by_name));
  }
  template <class T>
  CLI::Option* operator()(T RenderSettings::*) const {
    const SettingField& field = f;
    RenderSettings& settings = s;
    const auto problem = [&field](const std::string& t) {
      RenderSettings scratch;
      return set_from_text(field, t, scratch);
    };
    return add(app.add_option_function<std::string>(
                      f.option, [&field, &settings](const std::string& t) { set_from_text(field, t, settings); },
                      f.help)
                   ->check(refusing(f.option, problem)));
  }
};

// --out-denoised and --denoiser, of a render and of a merge.
void add_denoised_options(CLI::App& app, std::string& out, std::string& denoiser, const std::string& help) {
  app.add_option("--out-denoised", out, help);
  app.add_option("--denoiser", denoiser,
                 "--out-denoised's filter: quality (first-order regression) or fast (a-trous)")
      ->capture_default_str()
      ->check(one_of("--denoiser", {"quality", "fast"}))
      ->type_name("quality|fast");
}

void add_app_options(CLI::App& app, CommandLine& o) {
  app.add_flag("--headless", o.headless,
               "Render without a window and write --out/--out-float/--stats: --frames N passes, "
               "else the scene's target_spp samples per pixel");
  app.add_option("--scene", o.scene_name,
                 "Scene name (NAME.json in $WHISKER_SCENES, $WHISKER_ASSETS/scenes, ./assets/scenes, then the data folder beside the binary) or path to a scene file")
      ->capture_default_str();
  app.add_option("--mesh", o.mesh, "Use this OBJ file for the scene's meshes");
  app.add_option("FILE", o.file,
                 "A scene file (.json) to open, or an OBJ mesh (.obj) to show in the cat "
                 "scene's room in place of the cat, scaled to fit where the cat stands");
  int_in(app.add_option("--frames", o.frames,
                 "Passes of --spp samples per pixel. Headless: render N passes and write the "
                 "outputs (default: the scene's target_spp samples, see --target-spp). Viewer: "
                 "render N passes, then keep the window open; with --screenshot, save it and exit"),
         1, 1 << 24);
  int_in(app.add_option("--threads", o.threads, "Worker threads (0 = all)"), 0, 1024);
  app.add_option("--light", o.light, "Light position x,y,z");
  number_in(app.add_option("--intensity", o.intensity, "Light intensity"), 0.0, 1e30);
  app.add_option("--out", o.out_png, "PNG output (the report's display mapping)");
  app.add_option("--out-float", o.out_float,
                 "Linear float output (.pfm or .exr; see --float-units); an EXR header holds "
                 "the scene, spp, seed, camera, settings and render time");
  app.add_option("--stats", o.stats_json, "Write render statistics as JSON");
  add_denoised_options(app, o.out_denoised, o.denoiser,
                       "Headless: also write a denoised copy of the image (.png, .pfm or .exr; the raw "
                       "outputs stay as they are), with its estimated error in the stats");
  app.add_flag("--features", o.features, "Headless: keep the denoiser's feature buffers (as --out-denoised "
               "does) in --out-sum and --out-float's EXR, so that a merge of parts can be denoised");
  app.add_flag("--denoised", o.denoised_view, "Viewer: show the denoised image (fast filter); key D switches");
  app.add_option("--screenshot", o.screenshot, "Viewer: save the window after --frames N passes and exit");
  int_in(app.add_option("--edit-after", o.edit_after,
                        "Viewer script: apply --edit-light after K passes"),
         0, 1 << 24);
  app.add_option("--edit-light", o.edit_light, "Viewer script: new light position x,y,z");
  app.add_option("--edit-orbit", o.edit_orbit,
                 "Viewer script: after --edit-after K passes, orbit the camera by dx,dy radians "
                 "(as a left drag)");
  app.add_option("--edit-toggle", o.edit_toggle,
                 "Viewer script: after --edit-after K passes, switch a boolean setting: " +
                     boolean_setting_keys())
      ->check(refusing("--edit-toggle", [](const std::string& t) {
        return boolean_setting(t) ? std::string() : "expected " + boolean_setting_keys();
      }))
      ->type_name("NAME");
  app.add_option("--edit-log", o.edit_log,
                 "Viewer: write a line per drawn frame and per edit (times, generations, "
                 "samples) to this file, for bench/viewer_latency.sh");
  app.add_flag("--quiet", o.quiet, "No progress line");
  number_in(app.add_option("--progress", o.progress_every,
                           "Headless, stderr not a terminal (a pipe, a log): a progress line "
                           "every SECONDS (default 5)"),
            0.01, 1e9);
  // Checked in check_outputs, in the words of every other refusal.
  app.add_option("--float-units", o.float_units,
                 "--out-float values: scene (radiance) or display (1.0 = the PNG's white, "
                 "255^2.2 radiance)")
      ->capture_default_str()
      ->check(one_of("--float-units", {"scene", "display"}))
      ->type_name("scene|display");
  app.add_option("--samples", o.samples,
                 "Headless: render sample indices A to B-1 of every pixel (A:B), in passes of --spp");
  app.add_option("--resume", o.resume,
                 "Headless: continue the render in this accumulation file (.exr from --out-sum)");
  app.add_option("--out-sum", o.out_sum,
                 "Headless: accumulation file (.exr): exact sums, sample range, scene and settings");
  number_in(app.add_option("--checkpoint", o.checkpoint,
                 "Headless: also write --out-sum while rendering, at most every SECONDS (0: every "
                 "pass), to --resume a killed render"),
            0.0, 1e9);
}

// What was given for `option` (its first value).
std::string given_text(const CLI::App& app, const char* option) {
  const auto& r = app.get_option(option)->results();
  return r.empty() ? std::string() : cut_for_message(r.front());
}

// Options that go together, or not: CLI11 refuses the command line
// (->needs, ->excludes), and the first rule broken says why in Whisker's
// words (one_line_error).
struct Pairing {
  const char* option;
  const char* other;
  bool needs;  // `option` needs `other`; else it excludes it
  std::string (*why)(const CLI::App& app);
};

std::string needs_viewer(const char* option) {
  return std::string(option) + " needs the viewer; drop --headless";
}
std::string needs_headless(const CLI::App&) {
  return "--samples, --resume, --out-sum and --checkpoint need --headless";
}

const Pairing kPairings[] = {
    {"--frames", "--target-spp", false,
     [](const CLI::App& a) {
       return "--frames " + given_text(a, "--frames") + " and --target-spp " +
              given_text(a, "--target-spp") + " both set the samples per pixel; give one";
     }},
    {"--samples", "--target-spp", false,
     [](const CLI::App& a) {
       return "--samples " + given_text(a, "--samples") + " sets the samples per pixel; drop --target-spp";
     }},
    {"--samples", "--frames", false,
     [](const CLI::App&) {
       return std::string("--samples A:B sets the passes (of --spp samples); drop --frames");
     }},
    {"--out-denoised", "--headless", true,
     [](const CLI::App&) { return std::string("--out-denoised needs --headless"); }},
    {"--features", "--headless", true, [](const CLI::App&) { return std::string("--features needs --headless"); }},
    {"--screenshot", "--headless", false, [](const CLI::App&) { return needs_viewer("--screenshot"); }},
    {"--denoised", "--headless", false, [](const CLI::App&) { return needs_viewer("--denoised"); }},
    {"--edit-after", "--headless", false, [](const CLI::App&) { return needs_viewer("--edit-after"); }},
    {"--edit-light", "--headless", false, [](const CLI::App&) { return needs_viewer("--edit-light"); }},
    {"--edit-orbit", "--headless", false, [](const CLI::App&) { return needs_viewer("--edit-orbit"); }},
    {"--edit-toggle", "--headless", false, [](const CLI::App&) { return needs_viewer("--edit-toggle"); }},
    {"--edit-log", "--headless", false, [](const CLI::App&) { return needs_viewer("--edit-log"); }},
    {"--samples", "--headless", true, needs_headless},
    {"--resume", "--headless", true, needs_headless},
    {"--out-sum", "--headless", true, needs_headless},
    {"--checkpoint", "--headless", true, needs_headless},
    {"--checkpoint", "--out-sum", true,
     [](const CLI::App&) { return std::string("--checkpoint needs --out-sum (the file it keeps up to date)"); }},
    {"--screenshot", "--frames", true,
     [](const CLI::App&) { return std::string("--screenshot needs --frames N"); }},
};

void pair_options(CLI::App& app) {
  for (const Pairing& p : kPairings) {
    CLI::Option* other = app.get_option(p.other);
    if (p.needs)
      app.get_option(p.option)->needs(other);
    else
      app.get_option(p.option)->excludes(other);
  }
}

// The first rule of kPairings the command line breaks, or "".
std::string broken_pairing(const CLI::App& app) {
  const auto given = [&app](const char* name) {
    const CLI::Option* o = app.get_option_no_throw(name);
    return o && o->count() > 0;
  };
  for (const Pairing& p : kPairings)
    if (given(p.option) && (p.needs ? !given(p.other) : given(p.other))) return p.why(app);
  return {};
}

// The option names of `app` ("--frames", ...).
std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* opt : app.get_options())
    for (const std::string& n : opt->get_lnames()) names.push_back("--" + n);
  return names;
}

// "-headless": one dash before a long name. CLI11 would read it as -h plus
// letters and print the help; say which option was meant instead.
std::string single_dash_option(int argc, char** argv, const CLI::App& app) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.size() < 3 || a[0] != '-' || !std::isalpha(static_cast<unsigned char>(a[1]))) continue;
    char* end = nullptr;
    std::strtod(a.c_str(), &end);
    if (end == a.c_str() + a.size()) continue;  // a number such as -inf: a value
    const std::string hint = closest("-" + a.substr(0, a.find('=')), option_names(app));
    return a + ": options start with two dashes" +
           (hint.empty() ? std::string(" (see --help)") : "; did you mean " + hint + "?");
  }
  return {};
}

// "--frames" last, with no value after it: "--frames: needs a value".
std::string missing_value(int argc, char** argv, const CLI::App& app) {
  const std::string last = argc > 1 ? argv[argc - 1] : "";
  if (last.rfind("--", 0) != 0) return {};
  const CLI::Option* opt = app.get_option_no_throw(last);
  if (!opt || opt->get_items_expected_min() == 0) return {};
  return last + ": needs a value (see --help)";
}

// A CLI11 error as one line: "--frames abc: expected an integer".
std::string one_line_error(const CLI::ParseError& e, const CLI::App& app) {
  if (dynamic_cast<const BadValue*>(&e)) return e.what();
  if (dynamic_cast<const CLI::ExcludesError*>(&e) || dynamic_cast<const CLI::RequiresError*>(&e))
    if (const std::string why = broken_pairing(app); !why.empty()) return why;
  if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
    std::vector<std::string> extras = app.remaining();
    if (!extras.empty()) {
      const std::string& a = extras.front();
      if (a.rfind("--", 0) == 0) {
        const std::string hint = closest(a.substr(0, a.find('=')), option_names(app));
        return "unknown option " + a +
               (hint.empty() ? std::string(" (see --help)") : "; did you mean " + hint + "?");
      }
      return "unexpected argument " + a + " (options start with --; see --help)";
    }
  }
  // A value missing at the end is found before parsing (missing_value); the
  // other mismatch is a one-value option given twice.
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e))
    for (const CLI::Option* opt : app.get_options())
      if (opt->count() > 1 && opt->get_items_expected_max() == 1)
        return opt->get_name() + ": given more than once; give it once";
  std::string m = e.what();
  std::replace(m.begin(), m.end(), '\n', ' ');
  return m;
}

// What the parser's failure does: --help and --version print and return 0;
// anything else is one line, "whisker: ...", and kUsageError.
int parse_failure(const CLI::ParseError& e, const CLI::App& app) {
  if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
  return usage_error(one_line_error(e, app));
}

}  // namespace

std::optional<int> parse_command_line(int argc, char** argv, CommandLine& out) {
  CLI::App app{"Whisker: a progressive path tracer for the report's scenes"};
  app.set_version_flag("--version", "whisker " WHISKER_VERSION);
  add_app_options(app, out);
  bool man = false;
  app.add_flag("--man-settings", man, "Print the settings' part of the man page")->group("");
  // One line, like every other refusal: "whisker: --frames: ...".
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "whisker: " + cut_for_message(e.what(), 1000) + " (see --help)\n";
  });
  const auto fields = setting_fields();
  std::vector<CLI::Option*> options;
  for (const SettingField& f : fields)
    options.push_back(std::visit(SettingOption{app, f, out.settings}, f.member));
  pair_options(app);
  if (const std::string why = single_dash_option(argc, argv, app); !why.empty())
    return usage_error(why);
  if (const std::string why = missing_value(argc, argv, app); !why.empty()) return usage_error(why);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_failure(e, app);
  }
  if (man) {
    std::fputs(settings_man_page().c_str(), stdout);
    return 0;
  }
  // An option given "" is an error, not an option left out (--out "" beside
  // --stats wrote no image, silently).
  for (const char* name : {"--scene", "--mesh", "--light", "--out", "--out-float", "--stats",
                           "--out-denoised", "--screenshot", "--edit-light", "--samples", "--resume", "--out-sum"}) {
    const CLI::Option* opt = app.get_option(name);
    for (const std::string& r : opt->results())
      if (r.empty()) return usage_error(std::string(name) + ": needs a value, got \"\" (see --help)");
  }
  if (const std::string why = apply_file_argument(out, app.count("FILE") > 0, app.count("--scene") > 0);
      !why.empty())
    return usage_error(why);
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (options[i]->count() > 0) out.given.push_back(&fields[i]);
  return std::nullopt;
}

std::optional<int> parse_merge_command_line(int argc, char** argv, MergeCommandLine& o) {
  CLI::App app{"Sums accumulation files (sample-range parts of one render) into one, exactly",
               "whisker merge"};
  app.add_option("parts", o.parts, "Accumulation files (--out-sum) of one scene and settings");
  app.add_option("--out", o.outs,
                 "Output: .exr (accumulation file, mergeable again), .pfm (mean radiance), "
                 ".png (the report's mapping); repeatable")
      ->allow_extra_args(false);
  app.add_option("--stats", o.stats_json, "Write the merged render's statistics as JSON");
  app.add_flag("--partial", o.partial,
               "Write the merge even if sample ranges are missing (warns; the .exr lists its ranges)");
  add_denoised_options(app, o.out_denoised, o.denoiser,
                       "Also write a denoised copy of the merged image (.png, .pfm or .exr), from the "
                       "parts' feature buffers (rendered with --features or --out-denoised)");
  if (const std::string why = missing_value(argc, argv, app); !why.empty())
    return usage_error("merge " + why);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_failure(e, app);
  }
  for (const char* name : {"--stats", "--out-denoised"})
    if (app.count(name) && app.get_option(name)->results().front().empty())
      return usage_error(std::string("merge ") + name + ": needs a value, got \"\" (see --help)");
  return std::nullopt;
}

}  // namespace whisker
