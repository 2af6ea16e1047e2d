#include "ray_bench.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>

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

}  // namespace whisker::bench
