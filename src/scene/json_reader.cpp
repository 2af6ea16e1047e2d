#include "scene/json_reader.h"

#include <cstdint>
#include <iterator>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/quote.h"
#include "scene/scene_error.h"
#include "scene/scene_memory.h"

namespace whisker {

using nlohmann::json;

std::string line_column(const std::string& text, std::size_t byte) {
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

namespace {

// The parser's view of the text: a pointer that counts the bytes taken
// through it. The parser reads one byte at a time through its own copy and
// never ahead of the token it reports, so when it reports '[' or '{' the
// count is one past that bracket.
class CountingReader {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  CountingReader(const char* at, std::size_t* taken) : at_(at), taken_(taken) {}
  reference operator*() const { return *at_; }
  CountingReader& operator++() {
    ++at_;
    ++*taken_;
    return *this;
  }
  CountingReader operator++(int) {
    CountingReader before = *this;
    ++*this;
    return before;
  }
  bool operator==(const CountingReader& other) const { return at_ == other.at_; }
  bool operator!=(const CountingReader& other) const { return at_ != other.at_; }

 private:
  const char* at_;
  std::size_t* taken_;
};

// Builds the document from the parser's events. Each value goes where the
// innermost open array or object says (an array's end, the slot its key
// made in an object); a key is placed in its object's map as it is read, so
// a key given twice is the one whose place is taken already: one lookup in
// the map the document needs anyway, no set beside it. The first such key
// is kept to be named once the text is known to be well formed (a syntax
// error after it is the file's first fault). The pass stops at nesting past
// kMaxDepth and after `max_values` values and keys.
class DocumentBuilder : public nlohmann::json_sax<json> {
 public:
  DocumentBuilder(std::size_t max_values, const std::size_t& taken)
      : max_values_(max_values), taken_(taken) {}

  bool null() override { return add(json()) != nullptr; }
  bool boolean(bool b) override { return add(json(b)) != nullptr; }
  bool number_integer(number_integer_t n) override { return add(json(n)) != nullptr; }
  bool number_unsigned(number_unsigned_t n) override { return add(json(n)) != nullptr; }
  bool number_float(number_float_t x, const string_t&) override { return add(json(x)) != nullptr; }
  bool string(string_t& s) override { return add(json(std::move(s))) != nullptr; }
  // JSON text has no binary values (only the binary formats do).
  bool binary(binary_t&) override { return false; }
  bool start_object(std::size_t) override { return open(json::value_t::object); }
  bool start_array(std::size_t) override { return open(json::value_t::array); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    if (!count()) return false;
    Open& o = open_.back();
    auto [it, fresh] = o.node->get_ref<json::object_t&>().try_emplace(std::move(k));
    if (!fresh && duplicate_.empty()) duplicate_ = field(it->first);
    o.key = &it->first;
    o.slot = &it->second;
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    std::string msg = e.what();
    if (const auto* syntax = dynamic_cast<const json::parse_error*>(&e)) {
      // nlohmann's description without its "[json.exception...] parse error at ...:" prefix.
      if (auto colon = msg.find(": "); colon != std::string::npos) msg = msg.substr(colon + 2);
      error_byte_ = syntax->byte ? syntax->byte - 1 : 0;
      has_error_byte_ = true;
    } else if (auto bracket = msg.find("] "); bracket != std::string::npos) {
      msg = msg.substr(bracket + 2);  // e.g. a number too large for a double
    }
    error_ = msg;
    return false;
  }

  json& document() { return root_; }
  // Whether the pass stopped past kMaxDepth, and at which byte.
  bool too_deep() const { return too_deep_; }
  std::size_t deep_byte() const { return deep_byte_; }
  bool too_many() const { return values_ > max_values_; }
  // Values and keys read (at most max_values + 1).
  std::size_t values() const { return values_; }
  // The syntax error's description ("" if none) and, when it has one, byte.
  const std::string& error() const { return error_; }
  bool has_error_byte() const { return has_error_byte_; }
  std::size_t error_byte() const { return error_byte_; }
  // "camera.width" of the first key given twice, or "".
  const std::string& duplicate() const { return duplicate_; }

 private:
  struct Open {
    json* node;                     // the array or object
    json* slot = nullptr;           // an object's: the value of the key being read
    const std::string* key = nullptr;
  };

  bool count() { return ++values_ <= max_values_; }
  // Places `v` where the next value goes; nullptr past max_values.
  json* add(json&& v) {
    if (!count()) return nullptr;
    if (open_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Open& o = open_.back();
    if (o.node->is_array()) {
      auto& elements = o.node->get_ref<json::array_t&>();
      elements.push_back(std::move(v));
      return &elements.back();
    }
    *o.slot = std::move(v);
    return o.slot;
  }
  // An array or object is placed before its elements: its parent does not
  // grow while it is open, so the pointer to it stays valid.
  bool open(json::value_t kind) {
    if (open_.size() >= std::size_t(kMaxDepth)) {
      too_deep_ = true;
      deep_byte_ = taken_ ? taken_ - 1 : 0;
      return false;
    }
    json* node = add(json(kind));
    if (!node) return false;
    open_.push_back({node});
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
      if (open_[i].node->is_object()) {
        if (!path.empty()) path.push_back('.');
        path.append(cut_for_message(*open_[i].key, 60));
      } else {
        path.push_back('[');
        path.append(std::to_string(open_[i].node->size() - 1)).push_back(']');
      }
    }
    if (!path.empty()) path.push_back('.');
    return path.append(cut_for_message(key));
  }

  json root_;
  std::vector<Open> open_;
  std::size_t max_values_;
  std::size_t values_ = 0;
  const std::size_t& taken_;
  bool too_deep_ = false;
  std::size_t deep_byte_ = 0;
  std::string error_;
  bool has_error_byte_ = false;
  std::size_t error_byte_ = 0;
  std::string duplicate_;
};

}  // namespace

json read_json(const std::string& text, const std::string& file) {
  const std::uint64_t memory = machine_memory();
  const std::uint64_t room = memory > text.size() ? memory - text.size() : 0;
  std::size_t taken = 0;
  DocumentBuilder builder(memory ? std::size_t(room / kDocumentBytesPerValue) : ~std::size_t(0), taken);
  const CountingReader first(text.data(), &taken), last(text.data() + text.size(), &taken);
  json::sax_parse(first, last, &builder);
  if (builder.too_deep())
    throw SceneError(file + ":" + line_column(text, builder.deep_byte()) +
                     ": arrays and objects nested deeper than " + std::to_string(kMaxDepth) + " levels");
  if (builder.too_many())
    throw SceneError(file + ": " +
                     memory_refusal("reading more than " + std::to_string(builder.values() - 1) + " values",
                                    text.size() + builder.values() * kDocumentBytesPerValue, memory));
  if (!builder.error().empty()) {
    if (builder.has_error_byte())
      throw SceneError(file + ":" + line_column(text, builder.error_byte()) + ": invalid JSON: " + builder.error());
    throw SceneError(file + ": invalid JSON: " + builder.error());
  }
  if (!builder.duplicate().empty()) throw SceneError(file + ": " + builder.duplicate() + ": given twice; keep one");
  return std::move(builder.document());
}

}  // namespace whisker
