#include "scene/settings.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace whisker {

namespace {

constexpr EnumName<SamplerKind> kSamplers[] = {{SamplerKind::Independent, "independent"},
                                               {SamplerKind::Sobol, "sobol"}};
constexpr EnumName<BvhMethod> kAccels[] = {{BvhMethod::Brute, "brute"},
                                           {BvhMethod::BBox, "bbox"},
                                           {BvhMethod::Midpoint, "midpoint"},
                                           {BvhMethod::Sah, "sah"}};

using R = RenderSettings;

// The table. A seed is read from JSON as a double, so the file keeps it to
// 2^53; the command line caps it the same way, so that every seed can be
// written to a scene file.
const SettingField kFields[] = {
    {"spp", "--spp", &R::spp, "Samples per pixel per pass", 1, 1 << 20, 1 << 16},
    {"max_depth", "--depth", &R::max_depth, "Max bounces after the camera hit", 0, 1000},
    {"indirect", "--indirect", &R::indirect, "Indirect light: diffuse bounces (Monte Carlo, cosine sampling)", 0, 0, 0, "", "indirect light"},
    {"fresnel", "--fresnel", &R::fresnel, "Fresnel at glass (Schlick): part of the light reflects", 0, 0, 0, "", "Fresnel"},
    {"aa", "--aa", &R::aa, "Anti-aliasing (Gaussian jitter)", 0, 0, 0, "", "anti-aliasing"},
    {"seed", "--seed", &R::seed, "Random seed", 0, 0x1p53},
    {"target_spp", "--target-spp", &R::target_spp, "Stop at this many samples per pixel (0 = never); headless renders this many unless "
     "--frames (give one of the two)",
     0, 1 << 30},
    {"accel", "--accel", &R::accel, "Triangle acceleration: none, a bounding box, a BVH split at the middle, or by the "
     "surface area heuristic"},
    {"sampler", "--sampler", &R::sampler, "Random numbers: independent (the report's) or sobol (Owen-scrambled Sobol points)"},
    {"zero_cutoff", "--zero-cutoff", &R::zero_cutoff, "End paths whose throughput is zero (same image, less time)", 0, 0, 0, "", "end dark paths"},
    {"split", "--split", &R::split,
     "Indirect paths leaving the 1st, 2nd, ... diffuse hit (1 = the report's)", 0, 0, 0, "4,4"},
    {"split_weights", "--split-weights", &R::split_weights,
     "Per channel r,g,b: paths that carry only low-weight channels split less", 0.01, 1.0, 0,
     "0.5,0.25,1"},
    {"connect", "--connect", &R::connect,
     "Light connections: each diffuse bounce also reaches a point the light shines on, one of the "
     "sample's shared light paths (MIS; on in the cat scene)", 0, 0,
     0, "", "light connections"},
};

std::string bounds(double lo, double hi) {
  std::ostringstream s;
  s << std::setprecision(16) << "[" << lo << ", " << hi << "]";
  return s.str();
}

// All of `text` a decimal integer, no sign but '-', no space: its value,
// past the 64-bit range the nearest end of it (so that "-1" is negative
// for an unsigned setting too, and 1e30 digits are out of range, not "not
// an integer"); nullopt if not an integer.
std::optional<long long> whole_integer(std::string_view text) {
  long long v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || end != text.data() + text.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) return text[0] == '-' ? LLONG_MIN : LLONG_MAX;
  if (ec != std::errc()) return std::nullopt;
  return v;
}

template <class T>
std::string integer_from_text(const SettingField& f, std::string_view text, T& out) {
  long long v = 0;
  const double hi = f.option_hi > 0 ? f.option_hi : f.hi;
  std::string why = read_integer(text, (long long)f.lo, (long long)hi, v);
  if (why.empty()) out = T(v);
  return why;
}

std::string split_from_text(const SettingField& f, std::string_view text, std::vector<int>& out) {
  // Each factor an integer in full, no sign or space: "4," and " 4" are
  // typing slips, not a tree.
  const std::string expected = std::string("expected integers separated by commas, e.g. ") + f.example;
  std::vector<int> factors;
  for (std::size_t start = 0;;) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string_view item = text.substr(start, comma - start);
    const auto k = whole_integer(item);
    if (!k) return expected;
    if (*k < 1 || *k > kMaxSplitFactor)
      return "factors must be in [1, " + std::to_string(kMaxSplitFactor) + "], got " +
             std::string(item.substr(0, 24));
    factors.push_back(int(*k));
    if (comma == text.size()) break;
    start = comma + 1;
  }
  if (std::string why = check_split(factors); !why.empty()) return why;
  out = factors;
  return {};
}

template <NamedEnum E>
std::string enum_from_text(std::string_view text, E& out) {
  return parse(text, out) ? std::string() : "expected " + name_list(out);
}

}  // namespace

std::span<const EnumName<SamplerKind>> enum_names(SamplerKind) { return kSamplers; }
std::span<const EnumName<BvhMethod>> enum_names(BvhMethod) { return kAccels; }

std::span<const SettingField> setting_fields() { return kFields; }

const SettingField& setting_field(std::string_view key) {
  for (const SettingField& f : kFields)
    if (key == f.key) return f;
  throw std::logic_error("no render setting \"" + std::string(key) + "\"");
}

std::optional<vec3> parse_vec3(std::string_view text) {
  const auto v = parse_point(text);
  if (!v) return std::nullopt;
  const vec3 f(*v);
  if (!std::isfinite(f.x) || !std::isfinite(f.y) || !std::isfinite(f.z)) return std::nullopt;
  return f;
}

std::string read_integer(std::string_view text, long long lo, long long hi, long long& out) {
  const auto v = whole_integer(text);
  if (!v) return "expected an integer";
  if (*v < lo || *v > hi)
    return "must be in " + bounds(double(lo), double(hi)) + ", got " + std::string(text.substr(0, 40));
  out = *v;
  return {};
}

bool read_number(std::string_view text, double& out) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    return false;
  out = v;
  return true;
}

std::optional<glm::dvec3> parse_point(std::string_view text) {
  // Three items between two commas, each read in full by read_number(): the
  // spaces and signs --intensity refuses are refused here too.
  glm::dvec3 v;
  for (int k = 0; k < 3; ++k) {
    const std::size_t comma = k < 2 ? text.find(',') : text.size();
    if (comma == std::string_view::npos || !read_number(text.substr(0, comma), v[k]))
      return std::nullopt;
    text.remove_prefix(k < 2 ? comma + 1 : comma);
  }
  return v;
}

std::string set_from_text(const SettingField& f, std::string_view text, RenderSettings& s) {
  struct Visit {
    const SettingField& f;
    std::string_view text;
    RenderSettings& s;
    std::string operator()(bool R::*m) const {
      if (text != "on" && text != "off") return "expected on or off";
      s.*m = text == "on";
      return {};
    }
    std::string operator()(int R::*m) const { return integer_from_text(f, text, s.*m); }
    std::string operator()(std::uint64_t R::*m) const { return integer_from_text(f, text, s.*m); }
    std::string operator()(BvhMethod R::*m) const { return enum_from_text(text, s.*m); }
    std::string operator()(SamplerKind R::*m) const { return enum_from_text(text, s.*m); }
    std::string operator()(std::vector<int> R::*m) const { return split_from_text(f, text, s.*m); }
    std::string operator()(vec3 R::*m) const {
      const auto v = parse_vec3(text);
      for (int c = 0; v && c < 3; ++c)
        if ((*v)[c] < float(f.lo) || (*v)[c] > float(f.hi))
          return "expected three numbers r,g,b in " + bounds(f.lo, f.hi) + ", e.g. " + f.example;
      if (!v)
        return "expected three numbers r,g,b in " + bounds(f.lo, f.hi) + ", e.g. " + f.example;
      s.*m = *v;
      return {};
    }
  };
  return std::visit(Visit{f, text, s}, f.member);
}

const SettingField* boolean_setting(std::string_view key) {
  for (const SettingField& f : kFields)
    if (key == f.key && std::holds_alternative<bool R::*>(f.member)) return &f;
  return nullptr;
}

std::string boolean_setting_keys() {
  std::vector<const char*> keys;
  for (const SettingField& f : kFields)
    if (std::holds_alternative<bool R::*>(f.member)) keys.push_back(f.key);
  std::string s;
  for (std::size_t i = 0; i < keys.size(); ++i)
    s += std::string(i == 0 ? "" : i + 1 == keys.size() ? " or " : ", ") + keys[i];
  return s;
}

namespace {

struct Syntax {
  const SettingField& f;
  double hi() const { return f.option_hi > 0 ? f.option_hi : f.hi; }
  std::string operator()(bool R::*) const { return "on|off"; }
  std::string operator()(int R::*) const { return "INT in " + bounds(f.lo, hi()); }
  std::string operator()(std::uint64_t R::*) const { return "UINT in " + bounds(f.lo, hi()); }
  template <NamedEnum E>
  std::string operator()(E R::*) const {
    std::string s;
    for (const auto& n : enum_names(E{})) s += std::string(s.empty() ? "" : "|") + n.name;
    return s;
  }
  std::string operator()(std::vector<int> R::*) const {
    return std::string("INT,... e.g. ") + f.example;
  }
  std::string operator()(vec3 R::*) const { return "R,G,B each in " + bounds(f.lo, f.hi); }
};

struct Text {
  const RenderSettings& s;
  std::string operator()(bool R::*m) const { return s.*m ? "on" : "off"; }
  std::string operator()(int R::*m) const { return std::to_string(s.*m); }
  std::string operator()(std::uint64_t R::*m) const { return std::to_string(s.*m); }
  template <NamedEnum E>
  std::string operator()(E R::*m) const { return to_string(s.*m); }
  std::string operator()(std::vector<int> R::*m) const { return split_to_string(s.*m); }
  std::string operator()(vec3 R::*m) const {
    std::ostringstream o;
    o << std::setprecision(9) << (s.*m).x << ',' << (s.*m).y << ',' << (s.*m).z;
    return o.str();
  }
};

}  // namespace

std::string value_syntax(const SettingField& f) { return std::visit(Syntax{f}, f.member); }

std::string value_text(const SettingField& f, const RenderSettings& s) {
  return std::visit(Text{s}, f.member);
}

void copy_field(const SettingField& f, const RenderSettings& from, RenderSettings& to) {
  std::visit([&](auto m) { to.*m = from.*m; }, f.member);
}

std::string check_split(const std::vector<int>& split) {
  if (split.empty()) return "must hold at least one factor";
  if (split.size() > std::size_t(kMaxSplitLevels))
    return "at most " + std::to_string(kMaxSplitLevels) + " factors, got " +
           std::to_string(split.size());
  long long paths = 1;
  for (int k : split) {
    if (k < 1 || k > kMaxSplitFactor)
      return "factors must be in [1, " + std::to_string(kMaxSplitFactor) + "], got " +
             std::to_string(k);
    paths *= k;
  }
  if (paths > kMaxSplitPaths)
    return "the factors' product (paths per sample) must be at most " +
           std::to_string(kMaxSplitPaths) + ", got " + std::to_string(paths);
  return {};
}

std::string split_to_string(const std::vector<int>& split) {
  std::string s;
  for (int k : split) {
    if (!s.empty()) s += ',';
    s += std::to_string(k);
  }
  return s;
}

}  // namespace whisker
