// The scene as plain data: what a scene file holds, before any acceleration.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/settings.h"

namespace whisker {

using glm::vec3;

// The report's four surface kinds. Hollow glass is a glass shell with an air
// bubble: two glass spheres, the inner one with its normal inverted (report
// section 2); it is expanded into those two shells when the scene is built.
enum class MaterialKind : std::uint8_t { Diffuse, Mirror, Glass, HollowGlass };

struct Material {
  MaterialKind kind = MaterialKind::Diffuse;
  vec3 albedo{1.0f};  // diffuse only
  float ior = 1.5f;   // glass and hollow glass

  bool operator==(const Material&) const = default;
};

struct SphereObject {
  std::string name;
  vec3 center{0.0f};
  float radius = 1.0f;
  float inner_radius = 0.0f;  // hollow glass: radius of the air bubble
  Material material;
};

struct TriangleMesh;  // geometry/mesh.h

struct MeshObject {
  std::string name;
  std::string path;     // as written in the scene file
  float scale = 1.0f;   // applied first
  vec3 translate{0.0f};  // then this
  bool vertex_normals = false;  // shade with the file's normals (else flat)
  Material material;
  // Loaded, scaled and translated triangles; shared between scene copies.
  std::shared_ptr<const TriangleMesh> mesh;
};

struct PointLight {
  vec3 position{-10.0f, 20.0f, 40.0f};
  float intensity = 2e10f;

  bool operator==(const PointLight&) const = default;
};

struct Camera {
  vec3 position{0.0f, 0.0f, 55.0f};
  vec3 look_at{0.0f, 0.0f, 0.0f};
  vec3 up{0.0f, 1.0f, 0.0f};
  float fov_deg = 60.0f;  // across the image width
  int width = 512;
  int height = 512;

  bool operator==(const Camera&) const = default;
};


struct Scene {
  std::string name;
  std::string source_path;  // the scene file, for messages and mesh paths
  std::vector<SphereObject> spheres;
  std::vector<MeshObject> meshes;
  PointLight light;
  Camera camera;
  RenderSettings settings;
};

std::span<const EnumName<MaterialKind>> enum_names(MaterialKind);

}  // namespace whisker
