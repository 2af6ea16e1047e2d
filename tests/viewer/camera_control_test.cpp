// The mouse camera moves and the room the eye must stay in (viewer/camera_control.h).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "scene/scene_io.h"
#include "scene/world.h"
#include "viewer/camera_control.h"
#include "viewer/input.h"

using namespace whisker;

TEST(CameraControl, OrbitKeepsDistanceAndTarget) {
  Camera c;
  const float r = glm::length(c.position - c.look_at);
  orbit(c, 0.7f, -0.3f);
  EXPECT_NEAR(glm::length(c.position - c.look_at), r, 1e-3f * r);
  EXPECT_EQ(c.look_at, glm::dvec3(0.0));
  EXPECT_GT(std::fabs(c.position.x), 1.0f);
  EXPECT_GT(c.position.y, 1.0f);  // dragging up-screen lifts the eye (dy < 0)
}

TEST(CameraControl, OrbitStopsBeforeThePole) {
  Camera c;
  orbit(c, 0.0f, -10.0f);  // far past straight above
  const vec3 dir = vec3(glm::normalize(c.position - c.look_at));
  EXPECT_LT(glm::dot(dir, vec3(0, 1, 0)), std::cos(glm::radians(0.5f)));
  EXPECT_GT(glm::dot(dir, vec3(0, 1, 0)), std::cos(glm::radians(1.5f)));
}

TEST(CameraControl, PanFollowsTheMouse) {
  Camera c;  // at (0,0,55) looking at the origin, 60 degrees over 512 px
  const glm::dvec3 view = c.look_at - c.position;
  pan(c, 10.0f, 0.0f);
  // Dragging right moves the eye left by 10 pixels' worth at the target.
  const float per_px = 2.0f * 55.0f * std::tan(glm::radians(30.0f)) / 512.0f;
  EXPECT_NEAR(c.position.x, -10.0f * per_px, 1e-4f);
  EXPECT_NEAR(c.look_at.x, -10.0f * per_px, 1e-4f);
  EXPECT_LT(glm::length(c.look_at - c.position - view), 1e-4f);
}

TEST(CameraControl, DollyScalesDistance) {
  Camera c;
  dolly(c, 0.5f);
  EXPECT_NEAR(c.position.z, 27.5f, 1e-4f);
  dolly(c, 0.0f);  // never onto the target itself
  EXPECT_GT(glm::length(c.position - c.look_at), 0.0f);
}

// The camera stays in the room: wheel notches out from the cat's camera
// (z = 55, the back wall at z = 60) and drags that would orbit the eye
// under the floor stop short of the surface, and the eye stays inside.
TEST(CameraControl, WheelAndDragsKeepTheEyeInTheRoom) {
  const Scene cat = load_scene(resolve_scene("cat"));
  const World world(cat);
  std::string why;
  ASSERT_TRUE(eye_inside_room(cat.camera, world, &why)) << why;
  Camera c = cat.camera;
  MouseCamera mouse;
  MouseInput wheel;
  wheel.wheel = -1.0f;  // one notch out
  for (int k = 0; k < 10; ++k) {
    bool stopped = false;
    mouse.update(c, wheel, 1.0f, &world, &stopped);
    if (k == 0) {
      EXPECT_TRUE(stopped);
    }
    EXPECT_LT(c.position.z, 60.0) << "notch " << k;
    ASSERT_TRUE(eye_inside_room(c, world, &why)) << "notch " << k << ": " << why;
  }
  EXPECT_GT(c.position.z, 59.0);  // it went as far as the wall allows
  // A long left drag down: without the stop the eye orbits under the floor.
  Camera d = cat.camera;
  MouseInput press;
  press.clicked[0] = press.down[0] = true;
  mouse.update(d, press, 1.0f, &world);
  MouseInput drag;
  drag.down[0] = true;
  drag.dy = -25.0f;  // lowers the eye (orbit turns by -dy)
  for (int k = 0; k < 8; ++k) {
    mouse.update(d, drag, 1.0f, &world);
    ASSERT_TRUE(eye_inside_room(d, world, &why)) << "step " << k << ": " << why;
    // Above the floor: outside its sphere (centre (0, -1000, 0), radius 990).
    EXPECT_GT(glm::length(d.position - glm::dvec3(0.0, -1000.0, 0.0)), 990.0) << "step " << k;
  }
  // Without the World the same drag goes below the floor: the test can fail.
  Camera free = cat.camera;
  MouseCamera m2;
  m2.update(free, press, 1.0f);
  for (int k = 0; k < 8; ++k) m2.update(free, drag, 1.0f);
  EXPECT_FALSE(eye_inside_room(free, world));
}

TEST(CameraControl, AnEyeBehindTheWallIsReported) {
  const Scene cat = load_scene(resolve_scene("cat"));
  const World world(cat);
  Camera c = cat.camera;
  c.position.z = 61.1;  // one old wheel notch out
  std::string why;
  EXPECT_FALSE(eye_inside_room(c, world, &why));
  EXPECT_NE(why.find("behind a surface"), std::string::npos) << why;
}
