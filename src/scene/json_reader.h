// Reading a scene file's text into a JSON document in one pass over it: the
// parser's SAX events build the document, and on the way the pass refuses
// nesting too deep, more values than the machine's memory holds, and a key
// given twice in one object (which the library's own parse would take
// silently, keeping the last: {"width": 64, "width": 8192}).
#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace whisker {

// The deepest nesting of arrays and objects a scene file may have. A scene
// needs 5 levels (spheres[0].material.albedo); each level costs the parser
// about 80 bytes a byte of input ("[[[[..."), so the cap bounds memory too.
constexpr int kMaxDepth = 64;
// What the parsed document takes a value (number, string, array, object,
// or an object's key), at most, besides the text of its strings: about 100
// bytes for an empty object in an array. With the file's own bytes this is
// what reading a scene needs, checked against the machine's memory as the
// document grows.
constexpr std::size_t kDocumentBytesPerValue = 100;

// "line:column" (1-based) of a byte of `text`.
std::string line_column(const std::string& text, std::size_t byte);

// The document `text` holds. Throws SceneError naming `file`, one line:
// "FILE:L:C: invalid JSON: ..." for a syntax error, "FILE:L:C: arrays and
// objects nested deeper than 64 levels", "FILE: reading more than N values
// needs ...; this machine has ..." and "FILE: camera.width: given twice; keep
// one" (the path of the field, arrays indexed). Linear in the text: each key
// is looked up once, in its own object.
nlohmann::json read_json(const std::string& text, const std::string& file);

}  // namespace whisker
