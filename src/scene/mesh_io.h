// Loading triangle meshes from OBJ files, for the scene reader.
#pragma once

#include <stdexcept>
#include <string>

#include "geometry/mesh.h"

namespace whisker {

// Thrown for a mesh that cannot be loaded; what() names the file (and line
// where known).
struct MeshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Loads an OBJ file (polygons triangulated, negative indices allowed, missing
// material library a warning), applies p' = p * scale + translate.
TriangleMesh load_obj(const std::string& path, float scale, const glm::dvec3& translate);

}  // namespace whisker
