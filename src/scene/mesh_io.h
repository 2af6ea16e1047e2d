// Loading triangle meshes from OBJ files, for the scene reader.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/mesh.h"

namespace whisker {

// Thrown for a mesh that cannot be loaded; what() names the file (and line
// where known).
struct MeshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An OBJ file read and checked, not yet placed: the vertices as the file
// wrote them (in double), the triangles with their normal indices. A scene
// that names one file several times reads it once and places it for each.
struct ObjFile {
  std::string path;
  std::vector<double> coords;        // x, y, z of each vertex
  std::vector<glm::uvec3> triangles;
  std::vector<glm::uvec3> normal_idx;
  std::vector<bool> has_normals;      // per triangle: all three corners have one
  std::vector<vec3> normals;
  std::vector<std::string> warnings;
};
ObjFile read_obj(const std::string& path);
// The mesh of `obj` with p' = p * scale + translate, zero-area triangles
// dropped; it holds the vertices the faces use (in the file's order), and
// only those must stay finite.
TriangleMesh place_obj(const ObjFile& obj, float scale, const glm::dvec3& translate);

// A placement (p' = p * scale + translate) that fits `obj` in a box: the
// largest scale at which the vertices of its faces of non-zero area span at
// most `size` on each axis, and the translation that puts the middle of the
// bottom (least y) of their bounding box at `base`. Vertices no such face
// uses (a far stray point) play no part. Throws MeshError if no face has an
// area.
struct ObjPlacement {
  float scale = 1.0f;
  glm::dvec3 translate{0.0};
};
ObjPlacement fit_obj(const ObjFile& obj, const glm::dvec3& size, const glm::dvec3& base);

// Loads an OBJ file (polygons triangulated, negative indices allowed, missing
// material library a warning), applies p' = p * scale + translate.
TriangleMesh load_obj(const std::string& path, float scale, const glm::dvec3& translate);

}  // namespace whisker
