// Reading one JSON object of a scene file field by field, with messages that
// name the file and the field ("scene.json: settings.spp: must be in ...").
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "scene/quote.h"
#include "scene/scene_error.h"

namespace whisker {

// Reads fields of one JSON object, naming "file: field" in every error.
class Fields {
  using json = nlohmann::json;

 public:
  Fields(const json& j, std::string path, const std::string& file)
      : j_(j), path_(std::move(path)), file_(file) {
    if (!j_.is_object()) fail(path_, "must be an object");
  }

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw SceneError(file_ + ": " + (field.empty() ? "top level" : field) + ": " + what);
  }
  std::string field(const std::string& key) const {
    // Known keys are short; an unknown one may be megabytes, cut in messages.
    const std::string k = cut_for_message(key);
    return path_.empty() ? k : path_ + "." + k;
  }

  void only(std::initializer_list<const char*> allowed) const {
    only(std::vector<const char*>(allowed));
  }
  void only(const std::vector<const char*>& allowed) const {
    for (const auto& [key, value] : j_.items()) {
      if (std::none_of(allowed.begin(), allowed.end(),
                       [&key = key](const char* a) { return key == a; })) {
        std::string list;
        for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
        fail(field(key), "unknown key (expected one of: " + list + ")");
      }
    }
  }

  bool has(const char* key) const { return j_.contains(key); }
  const json& at(const char* key) const {
    if (!j_.contains(key)) fail(field(key), "missing");
    return j_.at(key);
  }
  Fields object(const char* key) const { return Fields(at(key), field(key), file_); }

  double number(const char* key, double lo, double hi) const {
    const json& v = at(key);
    if (!v.is_number()) fail(field(key), "must be a number, got " + type(v));
    const double x = v.get<double>();
    check_range(field(key), x, lo, hi);
    return x;
  }
  double number(const char* key, double lo, double hi, double fallback) const {
    return has(key) ? number(key, lo, hi) : fallback;
  }
  long long integer(const char* key, long long lo, long long hi, long long fallback) const {
    if (!has(key)) return fallback;
    const json& v = at(key);
    if (!v.is_number_integer()) fail(field(key), "must be an integer, got " + type(v));
    // An unsigned value past the signed range would read as negative.
    const bool past = v.is_number_unsigned() && v.get<unsigned long long>() > 0x7fffffffffffffffull;
    const long long x = past ? hi : v.get<long long>();
    if (past || x < lo || x > hi)
      fail(field(key), "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                           "], got " + v.dump());
    return x;
  }
  bool boolean(const char* key, bool fallback) const {
    if (!has(key)) return fallback;
    const json& v = at(key);
    if (!v.is_boolean()) fail(field(key), "must be true or false, got " + type(v));
    return v.get<bool>();
  }
  std::string string(const char* key) const {
    const json& v = at(key);
    if (!v.is_string()) fail(field(key), "must be a string, got " + type(v));
    return v.get<std::string>();
  }
  std::string string(const char* key, const std::string& fallback) const {
    return has(key) ? string(key) : fallback;
  }
  // Three numbers in [lo, hi], as written (double): positions.
  glm::dvec3 point(const char* key, double lo, double hi) const {
    const json& v = at(key);
    if (!v.is_array() || v.size() != 3)
      fail(field(key), "must be an array of 3 numbers, got " + type(v));
    glm::dvec3 out;
    for (int i = 0; i < 3; ++i) {
      const std::string f = field(key) + "[" + std::to_string(i) + "]";
      if (!v[i].is_number()) fail(f, "must be a number, got " + type(v[i]));
      const double x = v[i].get<double>();
      check_range(f, x, lo, hi);
      out[i] = x;
    }
    return out;
  }
  glm::dvec3 point(const char* key, double lo, double hi, const glm::dvec3& fallback) const {
    return has(key) ? point(key, lo, hi) : fallback;
  }
  // The same rounded to float: colours, directions.
  glm::vec3 vector(const char* key, double lo, double hi) const { return glm::vec3(point(key, lo, hi)); }
  glm::vec3 vector(const char* key, double lo, double hi, glm::vec3 fallback) const {
    return has(key) ? vector(key, lo, hi) : fallback;
  }
  glm::vec3 direction(const char* key) const {
    const glm::vec3 v = vector(key, -1e30, 1e30);
    if (v.x == 0.0f && v.y == 0.0f && v.z == 0.0f) fail(field(key), "must not be zero-length");
    return v;
  }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  const json& raw() const { return j_; }

 private:
  static std::string type(const json& v) {
    if (v.is_number()) return "number " + v.dump();
    if (v.is_string()) return "string " + v.dump();
    return v.type_name();
  }
  void check_range(const std::string& f, double x, double lo, double hi) const {
    if (!std::isfinite(x)) fail(f, "must be finite");
    if (x < lo || x > hi) {
      // The value as the file wrote it (shortest round trip of the double).
      fail(f, "must be in [" + shortest(lo) + ", " + shortest(hi) + "], got " + shortest(x));
    }
  }

  const json& j_;
  std::string path_;
  const std::string& file_;
};

}  // namespace whisker
