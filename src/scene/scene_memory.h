// What reading and rendering a scene will need, estimated before either
// starts, against what the machine has: these, not counts of values,
// pixels or objects, are the limits of a scene.
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace whisker {

// The film's buffers a pixel in a headless render: its double sums (32
// bytes), two snapshots of them (64), three output images (36).
constexpr std::uint64_t kFilmBytesPerPixel = 132;
std::uint64_t film_bytes(std::uint64_t width, std::uint64_t height);
// The objects' part: each sphere (the scene's record, the World's copy, the
// object-level BVH and what its build holds), each distinct mesh's
// triangles and vertices once however often it is placed (the scene's,
// the World's copy and BVH), each placement.
std::uint64_t object_bytes(const Scene& scene);
// The machine's memory: its physical pages.
std::uint64_t machine_memory();
// "4.8 TB", "23 GB", "512 MB" (units of 1024): up to two digits after
// rounding, up (a need) or down (what there is).
std::string memory_text(std::uint64_t bytes, bool round_up);
// "WHAT needs N; this machine has M" if need > have, else "".
std::string memory_refusal(const std::string& what, std::uint64_t need, std::uint64_t have);

// Throws SceneError naming `file` if rendering `scene` (its film and its
// objects) would not fit the machine, naming what it holds.
void check_render_memory(const Scene& scene, const std::string& file);

}  // namespace whisker
