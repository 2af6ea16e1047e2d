// viewer/hover_delay.h: a tooltip waits for the pointer to rest, never shows
// with a button held, nor under a pointer that has not moved since start-up.
#include "viewer/hover_delay.h"

#include <gtest/gtest.h>

namespace whisker {
namespace {

constexpr unsigned long long kWidget = 7, kOther = 9;

TEST(HoverDelay, NoTooltipUnderAPointerThatNeverMoved) {
  HoverDelay h;
  for (double t = 0.0; t < 5.0; t += 0.1) {
    h.begin_frame(t, false, false);
    EXPECT_FALSE(h.due(kWidget)) << t;
  }
}

TEST(HoverDelay, ShowsAfterTheRestAndStaysWhileHovered) {
  HoverDelay h;
  h.begin_frame(0.0, true, false);
  EXPECT_FALSE(h.due(kWidget));
  EXPECT_TRUE(h.waiting());
  h.begin_frame(0.3, false, false);
  EXPECT_FALSE(h.due(kWidget));
  h.begin_frame(HoverDelay::kRestSeconds + 0.01, false, false);
  EXPECT_TRUE(h.due(kWidget));
  EXPECT_FALSE(h.waiting());
  // A move within the same widget keeps it.
  h.begin_frame(0.7, true, false);
  EXPECT_TRUE(h.due(kWidget));
  // Another widget waits for its own rest.
  h.begin_frame(0.8, true, false);
  EXPECT_FALSE(h.due(kOther));
  h.begin_frame(0.8 + HoverDelay::kRestSeconds + 0.01, false, false);
  EXPECT_TRUE(h.due(kOther));
}

TEST(HoverDelay, NeverWithAButtonHeld) {
  HoverDelay h;
  h.begin_frame(0.0, true, false);
  h.due(kWidget);
  h.begin_frame(1.0, false, false);
  EXPECT_TRUE(h.due(kWidget));
  // A drag starts: the tooltip goes and stays away while the button is down.
  for (double t = 1.1; t < 3.0; t += 0.1) {
    h.begin_frame(t, false, true);
    EXPECT_FALSE(h.due(kWidget)) << t;
  }
  // Released: it waits for a rest again.
  h.begin_frame(3.0, false, false);
  EXPECT_FALSE(h.due(kWidget));
  h.begin_frame(3.0 + HoverDelay::kRestSeconds + 0.2, false, false);
  EXPECT_TRUE(h.due(kWidget));
}

// Leaving the widget (a frame where nothing hovered asks) starts over.
TEST(HoverDelay, LeavingAndComingBackWaitsAgain) {
  HoverDelay h;
  h.begin_frame(0.0, true, false);
  h.due(kWidget);
  h.begin_frame(1.0, false, false);
  EXPECT_TRUE(h.due(kWidget));
  h.begin_frame(1.1, true, false);  // over nothing
  h.begin_frame(1.2, true, false);
  EXPECT_FALSE(h.due(kWidget));
}

}  // namespace
}  // namespace whisker
