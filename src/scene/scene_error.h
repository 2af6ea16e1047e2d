// The error of scene files, apart from their reader so that the helpers that
// check a file's fields can throw it without the whole reader's interface.
#pragma once

#include <stdexcept>

namespace whisker {

// Thrown for a scene file that cannot be used. what() is one line naming the
// file, and the field ("spheres[2].radius") or line:column of a syntax error.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace whisker
