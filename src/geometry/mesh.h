// Triangle meshes: indexed triangles in world space (loaded by
// scene/mesh_io.h).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace whisker {

using glm::vec3;

struct TriangleMesh {
  std::vector<vec3> positions;          // world space (scale and translate applied)
  // The same before rounding to float: the file's numbers read in double,
  // scaled and translated in double. The World subtracts its render-space
  // origin from these, so a mesh far from the origin keeps its shape.
  std::vector<glm::dvec3> exact;
  std::vector<glm::uvec3> triangles;    // indices into positions
  std::vector<vec3> normals;            // optional per-vertex normals
  std::vector<glm::uvec3> normal_idx;   // per triangle: indices into normals (empty if none)
  std::size_t dropped_degenerate = 0;   // zero-area triangles dropped at load
  std::vector<std::string> warnings;    // e.g. "cat.mtl not found"
  // The placement these positions carry (p' = p * scale + translate), when
  // the scene reader shares the mesh between every placement of its file
  // (the file's first mention's). Objects placed otherwise are instances of
  // it (scene/world.h). Unset: the positions are those of every object
  // holding the mesh.
  struct Placement {
    float scale = 1.0f;
    glm::dvec3 translate{0.0};
  };
  std::optional<Placement> placed;
};

}  // namespace whisker
