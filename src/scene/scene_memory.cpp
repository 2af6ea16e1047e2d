#include "scene/scene_memory.h"

#include <algorithm>
#include <cstdio>
#include <unordered_set>

#include <unistd.h>

#include "geometry/mesh.h"
#include "scene/scene_error.h"

namespace whisker {

std::uint64_t film_bytes(std::uint64_t width, std::uint64_t height) {
  constexpr std::uint64_t kMost = ~std::uint64_t(0);
  if (width && height > kMost / kFilmBytesPerPixel / width) return kMost;  // past 16 EB: as much
  return width * height * kFilmBytesPerPixel;
}

std::uint64_t object_bytes(const Scene& scene) {
  // Measured peaks (a million spheres; the cat): a sphere about 400 bytes
  // (with the headless run's scene identity, scene_to_json's document of
  // it), a triangle about 300 (with the light buffer), a vertex 40.
  constexpr std::uint64_t kSphere = 400, kTriangle = 300, kVertex = 40, kPlacement = 200;
  std::uint64_t bytes = scene.spheres.size() * kSphere + scene.meshes.size() * kPlacement;
  std::unordered_set<const TriangleMesh*> counted;
  for (const MeshObject& m : scene.meshes)
    if (m.mesh && counted.insert(m.mesh.get()).second)
      bytes += m.mesh->triangles.size() * kTriangle + m.mesh->positions.size() * kVertex;
  return bytes;
}

std::uint64_t machine_memory() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), size = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? std::uint64_t(pages) * std::uint64_t(size) : 0;
}

std::string memory_text(std::uint64_t bytes, bool round_up) {
  static const char* const kUnits[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
  int unit = 0;
  unsigned __int128 unit_bytes = 1;
  while (bytes / unit_bytes >= 1024 && unit < 6) {
    unit_bytes *= 1024;
    ++unit;
  }
  // Whole units from 10 up, tenths below; rounded in integers, so that one
  // byte less than 24 GB is 23 GB (down) and one more 25 GB (up).
  const bool tenths = unit > 0 && bytes / unit_bytes < 10;
  const unsigned __int128 scaled = (unsigned __int128)bytes * (tenths ? 10 : 1);
  std::uint64_t q = std::uint64_t(scaled / unit_bytes);
  if (round_up && scaled % unit_bytes != 0) ++q;
  char buf[40];
  if (tenths)
    std::snprintf(buf, sizeof buf, "%llu.%llu %s", (unsigned long long)(q / 10),
                  (unsigned long long)(q % 10), kUnits[unit]);
  else
    std::snprintf(buf, sizeof buf, "%llu %s", (unsigned long long)q, kUnits[unit]);
  return buf;
}

std::string memory_refusal(const std::string& what, std::uint64_t need, std::uint64_t have) {
  if (have == 0 || need <= have) return {};  // an unknown machine refuses nothing
  return what + " needs " + memory_text(need, true) + "; this machine has " + memory_text(have, false);
}

void check_render_memory(const Scene& scene, const std::string& file) {
  std::size_t triangles = 0;
  for (const MeshObject& m : scene.meshes) triangles += m.mesh ? m.mesh->triangles.size() : 0;
  const std::string what = "rendering " + std::to_string(scene.camera.width) + " x " +
                           std::to_string(scene.camera.height) + " pixels, " +
                           std::to_string(scene.spheres.size()) + " spheres and " +
                           std::to_string(triangles) + " triangles";
  const std::uint64_t need =
      film_bytes(std::uint64_t(scene.camera.width), std::uint64_t(scene.camera.height)) + object_bytes(scene);
  if (const std::string why = memory_refusal(what, need, machine_memory()); !why.empty())
    throw SceneError(file + ": " + why);
}

}  // namespace whisker
