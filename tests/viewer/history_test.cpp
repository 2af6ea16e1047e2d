// Undo and redo of the edits (viewer/history.h).
#include <gtest/gtest.h>

#include "viewer/history.h"
#include "test_scenes.h"

using namespace whisker;

TEST(EditHistory, ADragIsOneStepAndUndoRedoWalkIt) {
  EditHistory h;
  Scene a = three_balls(), b = a, c = a;
  b.light.position.x = 5.0f;
  c.light.position.x = 9.0f;
  h.changed(a);  // a drag: a -> b -> c, one gesture
  h.changed(b);
  h.settle();
  EXPECT_EQ(h.steps(), 1u);
  Scene cur = c;
  ASSERT_TRUE(h.undo(cur));
  EXPECT_EQ(cur.light.position.x, a.light.position.x);  // back before the drag
  EXPECT_FALSE(h.can_undo());
  ASSERT_TRUE(h.redo(cur));
  EXPECT_EQ(cur.light.position.x, 9.0f);
  EXPECT_FALSE(h.redo(cur));
  // A new edit after an undo drops the redo branch.
  ASSERT_TRUE(h.undo(cur));
  h.changed(cur);
  EXPECT_FALSE(h.can_redo());
}
