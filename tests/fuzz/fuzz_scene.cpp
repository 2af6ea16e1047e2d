// libFuzzer harness for the scene reader: parse_scene on arbitrary text. Every
// mesh is replaced by one small OBJ (the --mesh option's path) so that the
// input cannot name files of the machine. A clean refusal (SceneError) is
// fine; any other exception, a crash or a sanitizer report is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "fuzz_common.h"
#include "scene/scene_io.h"

namespace {

const std::string& tiny_mesh() {
  static const std::string path = [] {
    static const char kObj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n";
    return whisker_fuzz::write_scratch("tiny.obj", kObj, sizeof kObj - 1).string();
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const whisker::Scene s = whisker::parse_scene(text, "fuzz.json", whisker_fuzz::scratch_dir(),
                                                  tiny_mesh());
    // What the renderer relies on from an accepted scene.
    if (s.camera.width < 1 || s.camera.height < 1) __builtin_trap();
    if (!std::isfinite(s.light.intensity)) __builtin_trap();
    for (const auto& sp : s.spheres)
      if (!(sp.radius > 0.0f) || !std::isfinite(sp.radius)) __builtin_trap();
    // The writer's output must read back.
    const std::string again = whisker::scene_to_json(s);
    (void)whisker::parse_scene(again, "fuzz-again.json", whisker_fuzz::scratch_dir(), tiny_mesh());
  } catch (const whisker::SceneError&) {
  }
  return 0;
}
