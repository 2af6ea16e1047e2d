#include "ray_bench.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "geometry/bvh.h"
#include "io/atomic_file.h"
#include "render/camera.h"
#include "render/sampler.h"
#include "render/sampling.h"
#include "scene/mesh_io.h"

namespace whisker::bench {

std::vector<Ray> read_rays(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw std::runtime_error(path + ": cannot open ray file");
  const std::streamsize size = in.tellg();
  constexpr std::streamsize kRecord = 7 * sizeof(float);
  if (size <= 0 || size % kRecord != 0)
    throw std::runtime_error(path + ": size " + std::to_string(size) +
                             " is not a positive multiple of 28 bytes");
  in.seekg(0);
  std::vector<float> f(static_cast<std::size_t>(size) / sizeof(float));
  in.read(reinterpret_cast<char*>(f.data()), size);
  if (!in) throw std::runtime_error(path + ": read failed");
  std::vector<Ray> rays(f.size() / 7);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const float* r = &f[7 * i];  // this machine is little-endian, as the files are
    rays[i] = Ray{vec3(r[0], r[1], r[2]), vec3(r[3], r[4], r[5]), 0.0f, r[6]};
  }
  return rays;
}

std::vector<Triangle> load_cat(const std::string& path) {
  const TriangleMesh m = load_obj(path, 0.6f, glm::dvec3(0.0, -10.0, 0.0));
  std::vector<Triangle> tris;
  tris.reserve(m.triangles.size());
  for (const auto& t : m.triangles)
    tris.push_back({m.positions[t.x], m.positions[t.y], m.positions[t.z]});
  return tris;
}

void write_rays(const std::string& path, const std::vector<Ray>& rays) {
  std::vector<float> f;
  f.reserve(rays.size() * 7);
  for (const Ray& r : rays) f.insert(f.end(), {r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.tmax});
  write_bytes_atomically(path, std::string_view(reinterpret_cast<const char*>(f.data()),
                                                f.size() * sizeof(float)));
}

std::vector<Ray> make_primary_rays() {
  const CameraFrame cam{Camera{}};  // the report's camera (scene.h's defaults)
  std::vector<Ray> rays;
  rays.reserve(std::size_t(cam.width) * std::size_t(cam.height));
  for (int i = 0; i < cam.height; ++i)
    for (int j = 0; j < cam.width; ++j)
      rays.push_back(Ray{vec3(cam.origin), cam.centre_direction(i, j), 0.0f, kInf});
  return rays;
}

std::vector<Ray> make_diffuse_rays(const std::vector<Triangle>& tris,
                                   const std::vector<Ray>& primary, std::uint64_t seed) {
  const Bvh bvh = Bvh::build(tris, BvhMethod::Sah);
  std::vector<Ray> rays;
  for (std::size_t k = 0; k < primary.size(); ++k) {
    Hit hit;
    if (!bvh.intersect(primary[k], hit)) continue;
    const Triangle& t = tris[hit.prim];
    vec3 n = glm::normalize(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
    if (glm::dot(n, primary[k].d) > 0.0f) n = -n;  // the side the ray came from
    const vec3 p = primary[k].o + hit.t * primary[k].d + 1e-3f * n;
    const Frame frame(n);
    Rng rng(std::uint32_t(k), 0, seed);
    for (int b = 0; b < 8; ++b) {
      const float u1 = rng.uniform(), u2 = rng.uniform();
      rays.push_back(Ray{p, cosine_direction(frame, u1, u2), 0.0f, kInf});
    }
  }
  return rays;
}

}  // namespace whisker::bench
