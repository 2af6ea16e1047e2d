// Triangle meshes as loaded from OBJ files.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace whisker {

using glm::vec3;

struct TriangleMesh {
  std::vector<vec3> positions;          // world space (scale and translate applied)
  std::vector<glm::uvec3> triangles;    // indices into positions
  std::vector<vec3> normals;            // optional per-vertex normals
  std::vector<glm::uvec3> normal_idx;   // per triangle: indices into normals (empty if none)
  std::size_t dropped_degenerate = 0;   // zero-area triangles dropped at load
  std::vector<std::string> warnings;    // e.g. "cat.mtl not found"
};

// Thrown for a mesh that cannot be loaded; what() names the file (and line
// where known).
struct MeshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Loads an OBJ file (polygons triangulated, negative indices allowed, missing
// material library a warning), applies p' = p * scale + translate.
TriangleMesh load_obj(const std::string& path, float scale, const vec3& translate);

}  // namespace whisker
