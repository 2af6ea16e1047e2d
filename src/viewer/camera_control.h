// Mouse camera moves on the scene's Camera: orbit around the look-at point,
// pan in the image plane, dolly along the view direction.
#pragma once

#include "scene/scene.h"

namespace whisker {

// Turns the camera around look_at: dx (radians) about `up`, dy (radians)
// about the camera's right axis; stops short of the poles so `up` stays valid.
void orbit(Camera& cam, float dx, float dy);
// Moves position and look_at together by (dx, dy) image pixels of the
// camera's image, so the look-at point follows the mouse.
void pan(Camera& cam, float dx_pixels, float dy_pixels);
// Scales the distance to look_at by `factor` (< 1 moves closer).
void dolly(Camera& cam, float factor);

}  // namespace whisker
