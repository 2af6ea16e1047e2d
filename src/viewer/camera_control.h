// Mouse camera moves on the scene's Camera: orbit around the look-at point,
// pan in the image plane, dolly along the view direction.
#pragma once

#include <string>

#include "scene/scene.h"

namespace whisker {

class World;

// Turns the camera around look_at: dx (radians) about `up`, dy (radians)
// about the camera's right axis; stops short of the poles so `up` stays valid.
void orbit(Camera& cam, float dx, float dy);
// Moves position and look_at together by (dx, dy) image pixels of the
// camera's image, so the look-at point follows the mouse.
void pan(Camera& cam, float dx_pixels, float dy_pixels);
// Scales the distance to look_at by `factor` (< 1 moves closer).
void dolly(Camera& cam, float factor);

// Keeps the eye out of surfaces: the move from `before` to `cam` (a drag or
// wheel step) is followed along a ray through `world` (render space, any
// World of the same geometry); if a surface lies on the way, the eye stops
// short of it by a margin (a hundredth of the distance to the look-at point,
// at least 1e-3), the look-at point moving by as much for a pan. Returns
// true if the move was shortened; the eye never crosses a surface.
bool stop_at_surfaces(const Camera& before, Camera& cam, const World& world);

// Whether the eye looks out of a closed room from inside it: rays along the
// six axes and the view direction each meet a surface from its front
// (opaque surfaces: diffuse and mirror; glass is looked through). Returns
// false, with what is wrong in `why`, when one misses everything or meets
// the back of a surface (the eye is outside the room or inside an object).
bool eye_inside_room(const Camera& cam, const World& world, std::string* why = nullptr);
// The same for any point p (the light; `view` one more direction to try),
// `who` naming it in `why`.
bool inside_room(const glm::dvec3& p, const glm::dvec3& view, const World& world, const char* who,
                 std::string* why = nullptr);

}  // namespace whisker
