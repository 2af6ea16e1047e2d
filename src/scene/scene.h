// The scene as plain data: what a scene file holds, before any acceleration.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

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
};

struct Camera {
  vec3 position{0.0f, 0.0f, 55.0f};
  vec3 look_at{0.0f, 0.0f, 0.0f};
  vec3 up{0.0f, 1.0f, 0.0f};
  float fov_deg = 60.0f;  // across the image width
  int width = 512;
  int height = 512;
};

// Where the estimator's random numbers come from: independent uniforms (the
// report's method) or Owen-scrambled Sobol points.
enum class SamplerKind : std::uint8_t { Independent, Sobol };

// Acceleration structure for the triangles (issue 4).
enum class AccelKind : std::uint8_t { Brute, BBox, Midpoint, Sah };

struct RenderSettings {
  int spp = 1;            // samples per pixel per pass
  int max_depth = 5;      // bounces after the camera hit (report: getColor(ray, 5))
  bool indirect = false;  // Monte Carlo diffuse interreflection
  bool fresnel = false;   // Schlick reflect/refract choice at glass
  bool aa = false;        // Gaussian pixel jitter, sigma 0.5 px
  std::uint64_t seed = 0;
  int target_spp = 0;     // stop accumulating here (0 = never)
  AccelKind accel = AccelKind::Sah;
  SamplerKind sampler = SamplerKind::Sobol;
  bool zero_cutoff = true;  // end paths whose throughput is exactly zero
  // Splitting (issue 6): at the d-th diffuse hit of a path (d = 0: the
  // first), split[d] indirect paths leave and their light is averaged; the
  // path up to there and its direct-light ray are shared by all of them.
  // Entries past the end are 1; {1} is the report's one path per sample.
  std::vector<int> split{4, 4};
  // Per colour channel: a path that still carries the channels C splits
  // round(split[d] * max over C of split_weights[c]) ways (at least 1), so
  // effort goes where the image's error is (issue 6: in the report's room
  // the blue channel holds most of it). Each path's count depends only on
  // its own past, so the estimate stays unbiased. All 1: plain `split`.
  vec3 split_weights{1.0f};
};

// Limits on RenderSettings::split; returns what is wrong, or "" if nothing.
constexpr int kMaxSplitFactor = 64, kMaxSplitLevels = 8, kMaxSplitPaths = 4096;
std::string check_split(const std::vector<int>& split);
// "4,4" from {4, 4}.
std::string split_to_string(const std::vector<int>& split);

struct Scene {
  std::string name;
  std::string source_path;  // the scene file, for messages and mesh paths
  std::vector<SphereObject> spheres;
  std::vector<MeshObject> meshes;
  PointLight light;
  Camera camera;
  RenderSettings settings;
};

const char* to_string(MaterialKind k);
const char* to_string(AccelKind k);
const char* to_string(SamplerKind k);
// The names above back to values; false for an unknown name.
bool parse(std::string_view s, MaterialKind& out);
bool parse(std::string_view s, AccelKind& out);
bool parse(std::string_view s, SamplerKind& out);

}  // namespace whisker
