// The debug views (viewer/debug_views.h).
#include <gtest/gtest.h>

#include "scene/scene_io.h"
#include "viewer/debug_views.h"

using namespace whisker;

// Debug views of the three balls: the centre ray meets the glass ball
// (centre 0, radius 10) head on, 45 units from the eye at z = 55; the
// bottom row sees the blue floor.
TEST(DebugViews, NormalsMaterialsAndDepthOfTheThreeBalls) {
  const Scene s = load_scene(resolve_scene("three-balls"));
  const int w = s.camera.width, h = s.camera.height;
  const auto px = [&](const DebugImage& d, int i, int j, int c) {
    return d.image.sum[(std::size_t(i) * w + j) * 3 + c];
  };
  const DebugImage n = render_debug_view(s, kViewNormals);
  EXPECT_NEAR(px(n, h / 2, w / 2, 0), 0.5f, 0.01f);
  EXPECT_NEAR(px(n, h / 2, w / 2, 1), 0.5f, 0.01f);
  EXPECT_NEAR(px(n, h / 2, w / 2, 2), 1.0f, 0.01f);  // facing the camera: +z
  EXPECT_NEAR(px(n, h - 1, w / 2, 1), 1.0f, 0.01f);  // the floor faces up: +y

  const DebugImage m = render_debug_view(s, kViewAlbedo);
  EXPECT_FLOAT_EQ(px(m, h / 2, w / 2, 0), kGlassColour.x);
  EXPECT_EQ(px(m, h - 1, w / 2, 0), 0.0f);  // floor albedo (0, 0, 1)
  EXPECT_EQ(px(m, h - 1, w / 2, 2), 1.0f);

  const DebugImage d = render_debug_view(s, kViewDepth);
  ASSERT_GT(d.far, 45.0f);
  EXPECT_NEAR((1.0f - px(d, h / 2, w / 2, 0)) * d.far, 45.0f, 0.05f);
  EXPECT_NE(debug_legend(d).find("depth"), std::string::npos);
}
