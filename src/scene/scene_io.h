// Scene files (JSON) to Scene and back, with messages that name the field.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_error.h"

namespace whisker {

// Where data (scenes/, cat.obj) is looked up, in this order: $WHISKER_ASSETS;
// assets/ in the working folder; the data folder next to the binary
// (<bin>/../share/whisker when installed, <bin>/assets in a build tree).
std::vector<std::filesystem::path> asset_dirs();
// Where a scene NAME is looked up: $WHISKER_SCENES, then scenes/ in each of
// asset_dirs(). scene_dirs_text() lists them for messages.
std::vector<std::filesystem::path> scene_dirs();
std::string scene_dirs_text();
// The first of scene_dirs() that exists.
std::filesystem::path scenes_dir();
// NAME -> the first DIR/NAME.json of scene_dirs() that exists (else the
// last candidate); anything with a '/' or ending in .json is a path.
std::filesystem::path resolve_scene(const std::string& name_or_path);
// Names of the scenes in scene_dirs(), sorted, each once.
std::vector<std::string> list_scenes();

// Parses and validates a scene file, loading its meshes. Throws SceneError.
// A non-empty mesh_override replaces every mesh's path (the --mesh option).
Scene load_scene(const std::filesystem::path& path, const std::string& mesh_override = {});
Scene parse_scene(const std::string& text, const std::string& source_name,
                  const std::filesystem::path& base_dir = {},
                  const std::string& mesh_override = {});

// Scene to JSON text (the format load_scene reads). Given the file it is for,
// mesh paths are written to find the OBJs each was loaded from: relative to
// that file's folder, or absolute when no relative path leads there. Without
// it they stay as the scene file wrote them.
std::string scene_to_json(const Scene& scene, const std::filesystem::path& file = {});
// The same as a document (its strings as the scene holds them: dump with
// error_handler_t::replace where they may not be UTF-8).
nlohmann::json scene_json(const Scene& scene, const std::filesystem::path& file = {});
// The camera alone as scene-file JSON ("camera": {...}).
std::string camera_to_json(const Camera& camera);
// The camera's object itself ({"position": ..., ...}).
nlohmann::json camera_json(const Camera& camera);

// Where a mesh path resolves: relative to the scene file, then in each of
// asset_dirs(). Throws SceneError naming them.
std::filesystem::path resolve_mesh(const std::string& path,
                                   const std::filesystem::path& base_dir,
                                   const std::string& field);

}  // namespace whisker
