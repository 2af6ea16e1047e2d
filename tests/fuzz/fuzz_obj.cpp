// libFuzzer harness for the OBJ loader: the input is written to a file and
// loaded. A clean refusal (MeshError) is fine; any other exception, a crash,
// a sanitizer report or a mesh that breaks its own invariants is a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"
#include "scene/mesh_io.h"  // the OBJ loader's API (load_obj, MeshError)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = whisker_fuzz::write_scratch("input.obj", reinterpret_cast<const char*>(data), size);
  try {
    const whisker::TriangleMesh m = whisker::load_obj(path.string(), 1.0f, whisker::vec3(0.0f));
    // What the BVH builders and the renderer rely on.
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k)
        if (t[k] >= m.positions.size()) __builtin_trap();
    if (!m.normal_idx.empty() && m.normal_idx.size() != m.triangles.size()) __builtin_trap();
    for (const auto& n : m.normal_idx)
      for (int k = 0; k < 3; ++k)
        if (n[k] >= m.normals.size()) __builtin_trap();
    if (m.triangles.empty()) __builtin_trap();  // load_obj refuses a mesh with no triangles
  } catch (const whisker::MeshError&) {
  }
  return 0;
}
