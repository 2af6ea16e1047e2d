// Which keys and mouse states give which action (viewer/input.h).
#include <gtest/gtest.h>

#include "viewer/camera_control.h"
#include "viewer/input.h"

using namespace whisker;

TEST(InputMapping, ShortcutKeysGiveTheirRequests) {
  KeyPresses keys;
  keys.space = keys.r = keys.s = keys.c = keys.d = keys.escape = true;
  PanelRequests req;
  map_keys(keys, false, false, req);
  EXPECT_TRUE(req.toggle_pause);
  EXPECT_TRUE(req.toggle_denoised);
  EXPECT_TRUE(req.restart);
  EXPECT_TRUE(req.save);
  EXPECT_TRUE(req.print_camera);
  EXPECT_TRUE(req.quit);

  PanelRequests only_r;
  KeyPresses r;
  r.r = true;
  map_keys(r, false, false, only_r);
  EXPECT_TRUE(only_r.restart);
  EXPECT_FALSE(only_r.toggle_pause || only_r.save || only_r.print_camera || only_r.quit ||
               only_r.toggle_denoised);
}

TEST(InputMapping, KeysAreIgnoredWhileImGuiTakesText) {
  KeyPresses keys;
  keys.space = keys.r = keys.s = keys.c = keys.d = keys.escape = true;
  PanelRequests req;
  map_keys(keys, true, false, req);  // e.g. typing "s" into the path field
  EXPECT_FALSE(req.toggle_pause || req.restart || req.save || req.print_camera || req.quit ||
               req.toggle_denoised);
  // A request the panel already made is kept.
  req.save = true;
  map_keys(keys, true, false, req);
  EXPECT_TRUE(req.save);
}

// Esc with a popup open (a dropdown's list, a question) closes it and quits
// nothing, also while the question holds the keyboard; with none, it quits.
TEST(InputMapping, EscClosesAnOpenPopupBeforeItQuits) {
  KeyPresses esc;
  esc.escape = true;
  for (bool keyboard : {false, true}) {
    PanelRequests req;
    map_keys(esc, keyboard, true, req);
    EXPECT_TRUE(req.close_popups) << keyboard;
    EXPECT_FALSE(req.quit) << keyboard;
  }
  PanelRequests req;
  map_keys(esc, false, false, req);
  EXPECT_TRUE(req.quit);
  EXPECT_FALSE(req.close_popups);
}

TEST(InputMapping, LeftDragOnTheImageOrbits) {
  Camera c;
  MouseCamera mouse;
  MouseInput in;
  in.clicked[0] = in.down[0] = true;
  mouse.update(c, in, 1.0f);  // press on the image: no move yet
  EXPECT_EQ(c.position, Camera().position);
  in.clicked[0] = false;
  in.dx = 50.0f;
  mouse.update(c, in, 1.0f);
  EXPECT_NE(c.position.x, 0.0f);
  EXPECT_EQ(c.look_at, glm::dvec3(0.0));  // orbit keeps the target
  // After the release the same motion does nothing.
  const glm::dvec3 after = c.position;
  in.down[0] = false;
  mouse.update(c, in, 1.0f);
  EXPECT_EQ(c.position, after);
}

// A press that arrives in the same frame as a pointer move: the move
// before the press is no part of the drag (the frame's delta, 40 units,
// is ignored), the move after it is (from the press position).
TEST(InputMapping, ADragStartsWhereTheButtonWentDown) {
  MouseInput in;
  in.clicked[0] = in.down[0] = true;
  in.dx = 40.0f;  // the pointer came 40 units this frame, then the press
  in.x = in.press_x[0] = 300.0f;
  in.y = in.press_y[0] = 200.0f;
  Camera c;
  MouseCamera mouse;
  mouse.update(c, in, 1.0f);
  EXPECT_EQ(c.position, Camera().position) << "the move before the press orbited";
  // Pressed at 290, the pointer at 300 by the frame: an orbit of 10 units,
  // the same as a press at 290 and a 10-unit move in the next frame.
  in.press_x[0] = 290.0f;
  Camera d;
  MouseCamera other;
  other.update(d, in, 1.0f);
  Camera e;
  orbit(e, -10.0f * 0.008f, 0.0f);
  EXPECT_NEAR(d.position.x, e.position.x, 1e-9);
  EXPECT_NEAR(d.position.z, e.position.z, 1e-9);
}

TEST(InputMapping, DragStartedOnThePanelNeverMovesTheCamera) {
  Camera c;
  MouseCamera mouse;
  MouseInput in;
  in.clicked[0] = in.down[0] = true;
  in.imgui_wants_mouse = true;  // pressed over the panel
  mouse.update(c, in, 1.0f);
  in.clicked[0] = false;
  in.imgui_wants_mouse = false;  // dragged out over the image
  in.dx = -80.0f;
  in.dy = 30.0f;
  mouse.update(c, in, 1.0f);
  EXPECT_EQ(c.position, Camera().position);
  // The wheel over the panel scrolls it, not the camera.
  in.down[0] = false;
  in.dx = in.dy = 0.0f;
  in.wheel = 2.0f;
  in.imgui_wants_mouse = true;
  mouse.update(c, in, 1.0f);
  EXPECT_EQ(c.position, Camera().position);
}

TEST(InputMapping, RightDragPansAndWheelDollies) {
  Camera c;
  MouseCamera mouse;
  MouseInput in;
  in.clicked[1] = in.down[1] = true;
  mouse.update(c, in, 1.0f);
  in.clicked[1] = false;
  in.dx = 10.0f;
  mouse.update(c, in, 2.0f);  // 2 image pixels per window unit: 5 pixels
  Camera expected;
  pan(expected, 5.0f, 0.0f);
  EXPECT_NEAR(c.position.x, expected.position.x, 1e-5f);
  EXPECT_NEAR(c.look_at.x, expected.look_at.x, 1e-5f);

  Camera d;
  MouseInput wheel;
  wheel.wheel = 1.0f;
  MouseCamera().update(d, wheel, 1.0f);
  EXPECT_NEAR(d.position.z, 55.0f * 0.9f, 1e-4f);
}

TEST(InputMapping, CtrlZAndCtrlYUndoAndRedoButNotWhileTyping) {
  KeyPresses k;
  k.undo = true;
  PanelRequests req;
  map_keys(k, false, false, req);
  EXPECT_TRUE(req.undo);
  EXPECT_FALSE(req.redo);
  k.undo = false;
  k.redo = true;
  PanelRequests typing;
  map_keys(k, true, false, typing);  // a text field has its own undo
  EXPECT_FALSE(typing.redo);
}
