#include "scene/settings_json.h"
#include "scene/quote.h"

#include <algorithm>
#include <climits>

namespace whisker {

namespace {

using nlohmann::json;
using R = RenderSettings;

// An integer (one factor, at the first diffuse hit) or an array of them.
std::vector<int> read_split(const Fields& f, const char* key) {
  const json& v = f.at(key);
  auto clamped = [](const json& x) {
    return int(std::clamp<long long>(x.get<long long>(), INT_MIN, INT_MAX));
  };
  std::vector<int> split;
  if (v.is_number_integer()) {
    split.push_back(clamped(v));
  } else if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!v[i].is_number_integer())
        f.fail(f.field(key) + "[" + std::to_string(i) + "]", "must be an integer");
      split.push_back(clamped(v[i]));
    }
  } else {
    f.fail(f.field(key), "must be an integer or an array of integers");
  }
  if (const std::string why = check_split(split); !why.empty()) f.fail(f.field(key), why);
  return split;
}

template <NamedEnum E>
E read_enum(const Fields& f, const char* key) {
  const std::string name = f.string(key);
  E e{};
  if (!parse(name, e))
    f.fail(f.field(key),
           "unknown " + std::string(key) + " \"" + cut_for_message(name) + "\" (expected " + name_list(e) + ")");
  return e;
}

struct Reader {
  const Fields& f;
  const SettingField& d;
  R& r;
  void operator()(bool R::*m) const { r.*m = f.boolean(d.key, r.*m); }
  void operator()(int R::*m) const {
    r.*m = int(f.integer(d.key, (long long)d.lo, (long long)d.hi, r.*m));
  }
  void operator()(std::uint64_t R::*m) const {
    r.*m = std::uint64_t(f.integer(d.key, (long long)d.lo, (long long)d.hi, (long long)(r.*m)));
  }
  void operator()(BvhMethod R::*m) const { r.*m = read_enum<BvhMethod>(f, d.key); }
  void operator()(SamplerKind R::*m) const { r.*m = read_enum<SamplerKind>(f, d.key); }
  void operator()(std::vector<int> R::*m) const { r.*m = read_split(f, d.key); }
  void operator()(vec3 R::*m) const { r.*m = f.vector(d.key, d.lo, d.hi, r.*m); }
};

struct Writer {
  json& j;
  const SettingField& d;
  const R& r;
  template <class T>
  void operator()(T R::*m) const {
    if constexpr (std::is_same_v<T, vec3>)
      j[d.key] = json::array({(r.*m).x, (r.*m).y, (r.*m).z});
    else if constexpr (NamedEnum<T>)
      j[d.key] = to_string(r.*m);
    else
      j[d.key] = r.*m;
  }
};

}  // namespace

void read_settings(const Fields& f, RenderSettings& out) {
  std::vector<const char*> keys;
  for (const SettingField& d : setting_fields()) keys.push_back(d.key);
  f.only(keys);
  for (const SettingField& d : setting_fields())
    if (f.has(d.key)) std::visit(Reader{f, d, out}, d.member);
}

json settings_to_json(const RenderSettings& s) {
  json j = json::object();
  for (const SettingField& d : setting_fields()) std::visit(Writer{j, d, s}, d.member);
  return j;
}

}  // namespace whisker
