// Render settings and their schema: one table row per setting gives its name,
// type, range, help text and member. The scene-file reader and writer, the
// command line (its typed options, --help, --edit-toggle), the man page
// (whisker --man-settings), the stats JSON and EXR header, the viewer's
// checkboxes and change detection all read that table, so a new setting is
// a member here and a row in settings.cpp.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <glm/vec3.hpp>

#include "geometry/bvh_method.h"

namespace whisker {

using glm::vec3;

// Where the estimator's random numbers come from: independent uniforms (the
// report's method) or Owen-scrambled Sobol points.
enum class SamplerKind : std::uint8_t { Independent, Sobol };


struct RenderSettings {
  int spp = 1;            // samples per pixel per pass
  int max_depth = 5;      // bounces after the camera hit (report: getColor(ray, 5))
  bool indirect = false;  // Monte Carlo diffuse interreflection
  bool fresnel = false;   // Schlick reflect/refract choice at glass
  bool aa = false;        // Gaussian pixel jitter, sigma 0.5 px
  std::uint64_t seed = 0;
  int target_spp = 0;     // stop accumulating here (0 = never)
  BvhMethod accel = BvhMethod::Sah;  // the triangles' acceleration structure
  SamplerKind sampler = SamplerKind::Sobol;
  bool zero_cutoff = true;  // end paths whose throughput is exactly zero
  // Splitting: at the d-th diffuse hit of a path (d = 0: the first), split[d]
  // indirect paths leave and their light is averaged; the path up to there
  // and its direct-light ray are shared by all of them. Entries past the end
  // are 1; {1} is the report's one path per sample.
  std::vector<int> split{4, 4};
  // Per colour channel: a path that still carries the channels C splits
  // round(split[d] * max over C of split_weights[c]) ways (at least 1), so
  // effort goes where the image's error is (in the report's room the blue
  // channel holds most of it). Each path's count depends only on its own
  // past, so the estimate stays unbiased. All 1: plain `split`.
  vec3 split_weights{1.0f};
  // Light connections (render/light_connect.h): at each diffuse vertex that
  // bounces, one more path, from the light to a surface point it shines on
  // (one of the sample's light cache, render/light_cache.h) and from there
  // to the vertex, combined with the cosine bounces by multiple importance
  // sampling.
  bool connect = false;

  bool operator==(const RenderSettings&) const = default;
};

// ---- names of enum values: one table per enum ---------------------------
template <class E>
struct EnumName {
  E value;
  const char* name;
};
std::span<const EnumName<SamplerKind>> enum_names(SamplerKind);
std::span<const EnumName<BvhMethod>> enum_names(BvhMethod);

template <class E>
concept NamedEnum = requires(E e) { enum_names(e); };

template <NamedEnum E>
const char* to_string(E e) {
  for (const auto& n : enum_names(e))
    if (n.value == e) return n.name;
  return "?";
}
// A name back to its value; false for an unknown name.
template <NamedEnum E>
bool parse(std::string_view s, E& out) {
  for (const auto& n : enum_names(out))
    if (s == n.name) {
      out = n.value;
      return true;
    }
  return false;
}
// "brute, bbox, midpoint or sah".
template <NamedEnum E>
std::string name_list(E e) {
  const auto names = enum_names(e);
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i)
    s += std::string(i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i].name;
  return s;
}

// ---- the schema ----------------------------------------------------------
struct SettingField {
  using Member = std::variant<bool RenderSettings::*, int RenderSettings::*,
                              std::uint64_t RenderSettings::*, BvhMethod RenderSettings::*,
                              SamplerKind RenderSettings::*, std::vector<int> RenderSettings::*,
                              vec3 RenderSettings::*>;
  const char* key;     // scene file and stats JSON ("max_depth")
  const char* option;  // command line ("--depth")
  Member member;
  const char* help;
  // Inclusive range of an integer, or of each component of a vec3.
  double lo = 0.0, hi = 0.0;
  // The command line's own upper bound where it is tighter (0: `hi`).
  double option_hi = 0.0;
  const char* example = "";  // a valid command-line value, for messages
  const char* label = nullptr;  // the viewer's checkbox, where not the key
};

// Every render setting, in scene-file order.
std::span<const SettingField> setting_fields();
// The row of `key`; the key must be in the table.
const SettingField& setting_field(std::string_view key);

// The boolean setting of `key` ("fresnel"), or nullptr if there is none.
const SettingField* boolean_setting(std::string_view key);
// "indirect, fresnel, aa, zero_cutoff or connect": the boolean settings' keys.
std::string boolean_setting_keys();
// What a command-line value of `f` looks like: "on|off", "INT in [1, 65536]",
// "brute|bbox|midpoint|sah", "R,G,B each in [0.01, 1]" (--help, the man page).
std::string value_syntax(const SettingField& f);
// The value of `f` in `s` as the command line writes it ("on", "4,4").
std::string value_text(const SettingField& f, const RenderSettings& s);

// Parses a command-line value of `f` into `s`; returns what is wrong ("" if
// nothing), to follow "OPTION VALUE: ". The command line's typed options
// check their text with the same readers (read_integer, the enum tables);
// its lists (split, split_weights) are read by this.
std::string set_from_text(const SettingField& f, std::string_view text, RenderSettings& s);
// Copies field `f` from `from` to `to`.
void copy_field(const SettingField& f, const RenderSettings& from, RenderSettings& to);

// "x,y,z" -> three finite numbers, or nullopt.
std::optional<vec3> parse_vec3(std::string_view text);
// The same in double (positions).
std::optional<glm::dvec3> parse_point(std::string_view text);
// The one reader of a number typed on the command line (each item of a list
// too): all of `text` a finite decimal as std::from_chars reads it, so no
// leading space or '+', no hex, no "nan"; out of double's range is refused.
bool read_number(std::string_view text, double& out);

// The one reader of an integer typed on the command line: all of `text` a
// decimal integer (no space, no '+'), in [lo, hi]. Returns what is wrong
// ("expected an integer", "must be in [lo, hi], got TEXT"), or "" with the
// value in `out`. A value past the 64-bit range is out of range too.
std::string read_integer(std::string_view text, long long lo, long long hi, long long& out);

// Limits on RenderSettings::split; returns what is wrong, or "" if nothing.
constexpr int kMaxSplitFactor = 64, kMaxSplitLevels = 8, kMaxSplitPaths = 4096;
std::string check_split(const std::vector<int>& split);
// "4,4" from {4, 4}.
std::string split_to_string(const std::vector<int>& split);

}  // namespace whisker
