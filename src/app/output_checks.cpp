// The command line's outputs checked before a render starts: folders that
// exist and are writable, nothing special replaced, no output over an input
// or over another output (cli.h: check_outputs).
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "app/cli.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "scene/quote.h"
#include "scene/scene_io.h"

namespace whisker {

namespace fs = std::filesystem;

namespace {

// An output path is usable if its folder exists and is writable, and the
// path names a regular file or nothing.
// Paths are shown shortened in the middle (path_for_message): a message
// over a path of PATH_MAX bytes still ends in its reason.
std::string check_output(const std::string& path, const char* option) {
  if (path.empty()) return {};
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  const std::string named = std::string(option) + " " + path_for_message(path) + ": ";
  if (const std::string why = folder_problem(dir.string()); !why.empty()) return named + why;
  // Never replace a directory, FIFO, device node or socket (nor what a
  // symbolic link points to) by a regular file.
  if (const std::string why = not_replaceable(path); !why.empty()) return named + why;
  if (::access(dir.c_str(), W_OK) != 0)
    return named + "folder " + path_for_message(dir.string()) +
           (errno == EACCES || errno == EROFS ? " is not writable" : ": " + std::string(std::strerror(errno)));
  return {};
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ea, eb;
  if (fs::equivalent(a, b, ea)) return true;
  const fs::path ca = fs::weakly_canonical(fs::absolute(a), ea),
                   cb = fs::weakly_canonical(fs::absolute(b), eb);
  return !ea && !eb && ca == cb;
}

std::string check_outputs(const CommandLine& cl, const Scene& scene) {
  const RenderSettings& s = scene.settings;
  // Which options go together is the parser's (cli.cpp, kPairings).
  // frames x spp samples per pixel must fit the target counter.
  if (cl.frames > 0 && std::uint64_t(cl.frames) * std::uint64_t(s.spp) > (1ull << 30))
    return "--frames " + std::to_string(cl.frames) + " x --spp " + std::to_string(s.spp) +
           " is more than 2^30 samples per pixel";
  const std::pair<std::string, const char*> outs[] = {
      {cl.out_png, "--out"}, {cl.out_float, "--out-float"}, {cl.stats_json, "--stats"},
      {cl.out_denoised, "--out-denoised"},
      {cl.screenshot, "--screenshot"}, {cl.out_sum, "--out-sum"}};
  for (const auto& [path, option] : outs) {
    if (auto err = check_output(path, option); !err.empty()) return err;
  }
  // No output may replace an input or another output of the same run; the
  // exception: --out-sum X --resume X continues the accumulation in place.
  // The inputs: the scene file, --resume, and every mesh the scene loaded
  // (from its file's paths or --mesh): --stats cat.obj replaced the mesh.
  std::vector<std::pair<std::string, const char*>> ins = {
      {resolve_scene(cl.scene_name).string(), "--scene"}, {cl.mesh, "--mesh"}, {cl.resume, "--resume"}};
  for (const MeshObject& m : scene.meshes) {
    try {
      ins.emplace_back(resolve_mesh(m.path, fs::path(scene.source_path).parent_path(), "").string(),
                       "mesh");
    } catch (const SceneError&) {
      // It was found when the scene loaded; nothing to compare if not now.
    }
  }
  for (std::size_t i = 0; i < std::size(outs); ++i) {
    const auto& [path, option] = outs[i];
    if (path.empty()) continue;
    for (std::size_t j = i + 1; j < std::size(outs); ++j)
      if (!outs[j].first.empty() && same_file(path, outs[j].first))
        return std::string(option) + " " + path + " and " + outs[j].second + " " + outs[j].first +
               " name the same file; give each output its own";
    for (const auto& [in, in_option] : ins) {
      if (in.empty() || (outs[i].second == std::string("--out-sum") && in_option == std::string("--resume")))
        continue;
      if (same_file(path, in))
        return std::string(option) + " " + path + ": is the " + in_option + " input; write it elsewhere";
    }
  }
  if (!cl.out_png.empty() && lower_extension(cl.out_png) != ".png")
    return "--out " + cl.out_png + ": must end in .png";
  if (!cl.out_float.empty()) {
    const auto ext = lower_extension(cl.out_float);
    if (ext != ".pfm" && ext != ".exr")
      return "--out-float " + cl.out_float + ": must end in .pfm or .exr";
    if (ext == ".exr" && !have_exr())
      return "--out-float " + cl.out_float + ": this build has no OpenEXR; use .pfm";
  }
  if (!cl.out_denoised.empty()) {
    const auto ext = lower_extension(cl.out_denoised);
    if (ext != ".png" && ext != ".pfm" && ext != ".exr")
      return "--out-denoised " + cl.out_denoised + ": must end in .png, .pfm or .exr";
    if (ext == ".exr" && !have_exr())
      return "--out-denoised " + cl.out_denoised + ": this build has no OpenEXR; use .pfm";
  }
  if (cl.float_units != "scene" && (cl.out_float.empty() || !cl.headless))
    return "--float-units " + cl.float_units + " is for --headless --out-float";
  if (!cl.edit_light.empty() && !parse_point(cl.edit_light))
    return "--edit-light " + cl.edit_light + ": expected three finite numbers x,y,z";
  if (cl.headless && cl.out_png.empty() && cl.out_float.empty() && cl.stats_json.empty() &&
      cl.out_sum.empty() && cl.out_denoised.empty())
    return "--headless needs at least one of --out, --out-float, --stats, --out-sum, --out-denoised";
  if (!cl.screenshot.empty() && lower_extension(cl.screenshot) != ".png")
    return "--screenshot " + cl.screenshot + ": must end in .png";
  return {};
}

}  // namespace whisker
