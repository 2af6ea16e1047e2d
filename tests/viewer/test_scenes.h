// A small scene for the viewer's tests: a mirror ball and a hollow glass
// ball, no meshes.
#pragma once

#include "scene/scene.h"

namespace whisker {

inline Scene three_balls() {
  Scene s;
  SphereObject a;
  a.name = "mirror";
  a.center = {-20, 0, 0};
  a.radius = 10;
  a.material.kind = MaterialKind::Mirror;
  s.spheres.push_back(a);
  SphereObject b = a;
  b.name = "hollow";
  b.center = {20, 0, 0};
  b.inner_radius = 9.8f;
  b.material.kind = MaterialKind::HollowGlass;
  s.spheres.push_back(b);
  return s;
}

}  // namespace whisker
