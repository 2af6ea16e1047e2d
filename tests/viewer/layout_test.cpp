// viewer/layout.h: the panel narrows, steps aside, and comes back with Tab.
#include "viewer/layout.h"

#include <gtest/gtest.h>

namespace whisker {
namespace {

constexpr float kFull = 400.0f, kMin = 280.0f;

// The default window for a 512 x 512 image: the panel at its full width.
TEST(PanelLayout, DefaultWindowKeepsTheFullPanel) {
  const PanelLayout l = layout_panel(PanelMode::Auto, 912, 800, 512, 512, kFull, kMin);
  EXPECT_TRUE(l.visible);
  EXPECT_FALSE(l.overlay);
  EXPECT_FLOAT_EQ(l.width, 400);
}

// 700 x 400: the image can be 400 high, so the panel gives up 100 units.
TEST(PanelLayout, ShortWindowNarrowsThePanelForTheImage) {
  const PanelLayout l = layout_panel(PanelMode::Auto, 700, 400, 512, 512, kFull, kMin);
  EXPECT_TRUE(l.visible);
  EXPECT_FALSE(l.overlay);
  EXPECT_FLOAT_EQ(l.width, 300);
  // Never below its narrowest: at 600 x 400 the image gets 320.
  EXPECT_FLOAT_EQ(layout_panel(PanelMode::Auto, 600, 400, 512, 512, kFull, kMin).width, kMin);
}

// 400 x 300: both do not fit; the panel steps aside, Tab puts it over the image.
TEST(PanelLayout, SmallWindowHidesThePanelTabShowsItOverTheImage) {
  const PanelLayout a = layout_panel(PanelMode::Auto, 400, 300, 512, 512, kFull, kMin);
  EXPECT_FALSE(a.visible);
  EXPECT_FLOAT_EQ(a.width, 0);
  const PanelMode shown = toggle_panel(a.visible);
  EXPECT_EQ(shown, PanelMode::Shown);
  const PanelLayout s = layout_panel(shown, 400, 300, 512, 512, kFull, kMin);
  EXPECT_TRUE(s.visible);
  EXPECT_TRUE(s.overlay);
  EXPECT_FLOAT_EQ(s.width, kMin);
  // Shown in a window where both fit, it is beside the image as in Auto.
  const PanelLayout wide = layout_panel(shown, 912, 800, 512, 512, kFull, kMin);
  EXPECT_FALSE(wide.overlay);
  EXPECT_FLOAT_EQ(wide.width, 400);
}

TEST(PanelLayout, HiddenGivesTheImageTheWholeWindow) {
  const PanelMode hidden = toggle_panel(true);
  EXPECT_EQ(hidden, PanelMode::Hidden);
  const PanelLayout l = layout_panel(hidden, 912, 800, 512, 512, kFull, kMin);
  EXPECT_FALSE(l.visible);
  EXPECT_FLOAT_EQ(l.width, 0);
}

// A wide image in a window narrower than image and panel: the panel takes
// its narrowest and the image the rest.
TEST(PanelLayout, WideImageGetsAllButTheNarrowestPanel) {
  const PanelLayout l = layout_panel(PanelMode::Auto, 1280, 800, 1024, 768, kFull, kMin);
  EXPECT_TRUE(l.visible);
  EXPECT_FLOAT_EQ(l.width, kMin);
}

}  // namespace
}  // namespace whisker
