// Checks of a scene file's text before it is parsed into a document:
// nesting depth, the values it holds (the document's memory), keys given
// twice. Each is one linear pass.
#pragma once

#include <cstddef>
#include <string>
#include <unordered_set>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/quote.h"
#include "scene/scene_error.h"

namespace whisker {

// "line:column" (1-based) of a byte of `text`.
inline std::string line_column(const std::string& text, std::size_t byte) {
  std::size_t line = 1, col = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

// The deepest nesting of arrays and objects a scene file may have. A scene
// needs 5 levels (spheres[0].material.albedo); each level costs the parser
// about 80 bytes a byte of input ("[[[[..."), so the cap bounds memory too.
constexpr int kMaxDepth = 64;
// What the parsed document takes a value (number, string, array, object,
// or an object's key), at most, besides the text of its strings: about 100
// bytes for an empty object in an array. With the file's own bytes this is
// what reading a scene needs (scene_io.cpp checks it against the machine's
// memory before the document is built).
constexpr std::size_t kDocumentBytesPerValue = 100;

// Refuses nesting deeper than kMaxDepth, naming the line and column where it
// goes past: one pass over the bytes, tracking strings and their escapes.
inline void check_nesting(const std::string& text, const std::string& file) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (ch == '\\') ++i;
      else if (ch == '"') in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      if (++depth > kMaxDepth)
        throw SceneError(file + ":" + line_column(text, i) + ": arrays and objects nested deeper than " +
                         std::to_string(kMaxDepth) + " levels");
    } else if (ch == ']' || ch == '}') {
      --depth;
    }
  }
}

// A first pass over the file with the parser's SAX interface, building
// nothing: finds a key given twice in one object, which the JSON parser
// would take silently, keeping the last ({"width": 64, "width": 8192}), and
// counts the values and keys. Linear in the file: each key is looked up once
// in the set of its own object. (nlohmann's parse callback is not: on the end
// of every object it rescans the enclosing array for discarded values.) It
// stops after `max_values` (the keys' sets take less than the document
// would).
class Prescan : public nlohmann::json_sax<nlohmann::json> {
 public:
  explicit Prescan(std::size_t max_values) : max_values_(max_values) {}

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    if (++values_ > max_values_) return false;
    if (!open_.empty()) {
      Open& o = open_.back();
      o.key = k;
      if (!o.keys.insert(k).second && found_.empty()) found_ = field(k);
    }
    return true;
  }
  // Syntax errors are left to the second, building parse, which names the line.
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }

  // "camera.width" of the first duplicate, or "".
  const std::string& found() const { return found_; }
  bool too_many() const { return values_ > max_values_; }
  // Values and keys read (at most max_values + 1).
  std::size_t values() const { return values_; }

 private:
  struct Open {
    bool object;
    std::string key;         // the object's key being read
    std::size_t index;       // the array's elements so far
    std::unordered_set<std::string> keys;
  };
  bool value() {
    if (!open_.empty() && !open_.back().object) ++open_.back().index;
    return ++values_ <= max_values_;
  }
  bool open(bool object) {
    if (!value()) return false;
    open_.push_back({object, {}, 0, {}});
    return true;
  }
  bool close() {
    if (!open_.empty()) open_.pop_back();
    return true;
  }
  // The path of `key` in the innermost object open.
  std::string field(const std::string& key) const {
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "." + s.
    std::string path;
    for (std::size_t i = 0; i + 1 < open_.size(); ++i) {
      if (open_[i].object) {
        if (!path.empty()) path.push_back('.');
        path.append(cut_for_message(open_[i].key, 60));
      } else {
        path.push_back('[');
        path.append(std::to_string(open_[i].index - 1)).push_back(']');
      }
    }
    if (!path.empty()) path.push_back('.');
    return path.append(cut_for_message(key));
  }
  std::vector<Open> open_;
  std::string found_;
  std::size_t max_values_;
  std::size_t values_ = 0;
};

}  // namespace whisker
