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
// Positions in a scene are kept in double as read: the file may place a
// small scene far from the origin (a 1e-3 room at 1e4), where float would
// round every coordinate by more than the room's details. World moves them
// to camera-relative float render space (world.h), which is where float is
// enough.
using glm::dvec3;

// The report's four surface kinds. Hollow glass is a glass shell with an air
// bubble: two glass spheres, the inner one with its normal inverted (report
// section 2); it is expanded into those two shells when the scene is built.
enum class MaterialKind : std::uint8_t { Diffuse, Mirror, Glass, HollowGlass };

// Glass: a solid ball, or a hollow one's two shells (both refract).
inline bool is_glass(MaterialKind k) { return k == MaterialKind::Glass || k == MaterialKind::HollowGlass; }

struct Material {
  MaterialKind kind = MaterialKind::Diffuse;
  vec3 albedo{1.0f};  // diffuse only
  float ior = 1.5f;   // glass and hollow glass

  bool operator==(const Material&) const = default;
};

struct SphereObject {
  std::string name;
  dvec3 center{0.0};
  float radius = 1.0f;
  float inner_radius = 0.0f;  // hollow glass: radius of the air bubble
  Material material;
};

struct TriangleMesh;  // geometry/mesh.h

struct MeshObject {
  std::string name;
  std::string path;     // as written in the scene file
  std::string file;     // the OBJ it resolved to and was loaded from (empty if not loaded)
  float scale = 1.0f;   // applied first
  dvec3 translate{0.0};  // then this
  bool vertex_normals = false;  // shade with the file's normals (else flat)
  Material material;
  // Loaded, scaled and translated triangles; shared between scene copies.
  std::shared_ptr<const TriangleMesh> mesh;
};

struct PointLight {
  dvec3 position{-10.0, 20.0, 40.0};
  float intensity = 2e10f;

  bool operator==(const PointLight&) const = default;
};

struct Camera {
  dvec3 position{0.0, 0.0, 55.0};
  dvec3 look_at{0.0, 0.0, 0.0};
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

// The triangles of the scene's meshes, a mesh placed twice counted twice
// (what World::triangle_count() traces).
std::size_t triangle_count(const Scene& scene);

// Whether a sphere or mesh of the scene is glass (solid or hollow).
bool has_glass(const Scene& scene);

// Whether every pass of `scene` gives the same image: no indirect light, no
// anti-aliasing jitter, no Fresnel choice at glass (off, or no glass), and the
// one point light. Its render is exact after one pass.
bool deterministic_estimate(const Scene& scene);

// The settings as far as they can change `scene`'s image: Fresnel off where
// there is no glass; without indirect light no splitting, split weights or
// light connections (they act on indirect paths only). Two settings with
// the same image settings render the same image, sample for sample.
RenderSettings image_settings(const Scene& scene);

// The largest coordinate a scene position may have (scene files, --light).
// Render space is relative to the camera (world.h), so what limits this is
// the distance across the scene in float, not the offset from the origin.
constexpr double kMaxCoordinate = 1e7;

// The unit vector from the camera towards look_at, computed in double and
// scaled before normalising, so that any two distinct positions give a
// finite direction (look_at != position).
vec3 view_direction(const Camera& camera);

// The camera's unit right vector, forward x up, for an up of any length
// (geometry/unit.h); zero when up is parallel to the view direction. The
// camera frame (render/camera.h) and the scene reader's check both use it.
vec3 camera_right(const Camera& camera, const vec3& forward);

}  // namespace whisker
