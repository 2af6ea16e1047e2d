# Viewer tests (included from tests/CMakeLists.txt when WHISKER_VIEWER is ON).

# The viewer's modules without a window: viewer/<module>_test.cpp tests
# src/viewer/<module>.cpp (camera moves, edit classification, input, ...).
file(GLOB WHISKER_VIEWER_TEST_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/viewer/*_test.cpp)
add_executable(viewer_logic_tests ${WHISKER_VIEWER_TEST_SOURCES}
  ${CMAKE_CURRENT_SOURCE_DIR}/viewer_readout_test.cpp)
target_include_directories(viewer_logic_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(viewer_logic_tests PRIVATE whisker_viewer GTest::gtest_main)
gtest_discover_tests(viewer_logic_tests DISCOVERY_TIMEOUT 60)

# The real binary under Xvfb; the tests skip themselves without xvfb-run.
add_executable(viewer_window_tests ${CMAKE_CURRENT_SOURCE_DIR}/viewer_window_test.cpp)
target_link_libraries(viewer_window_tests PRIVATE GTest::gtest_main
  nlohmann_json::nlohmann_json PkgConfig::STB)
target_compile_definitions(viewer_window_tests PRIVATE
  WHISKER_BIN="$<TARGET_FILE:whisker>"
  VIEWER_TEST_OUT="${CMAKE_CURRENT_BINARY_DIR}/viewer_out")
add_dependencies(viewer_window_tests whisker)
# One X server at a time: xvfb-run -a races when started in parallel, and the
# renders share the machine's cores.
gtest_discover_tests(viewer_window_tests DISCOVERY_TIMEOUT 60
  PROPERTIES TIMEOUT 600 RESOURCE_LOCK whisker_xvfb LABELS viewer)

# whisker_viewer_script_test(NAME SCRIPT TIMEOUT): a window test driven by
# xdotool from a shell script given the whisker binary; exit 77 (no xdotool
# or Xvfb) skips it. Each starts its own X server on a display number drawn
# at random (tests/viewer_drive.sh, in_xvfb), so they run beside each
# other and beside the rest: they spend most of their time holding keys and
# waiting for frames, a fraction of a core each (one render thread).
function(whisker_viewer_script_test name script timeout)
  add_test(NAME ${name} COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/${script} $<TARGET_FILE:whisker>)
  set_tests_properties(${name} PROPERTIES
    SKIP_RETURN_CODE 77 TIMEOUT ${timeout} LABELS viewer)
endfunction()

# Real mouse and keyboard input through xdotool (skipped without it).
whisker_viewer_script_test(ViewerInput.PanelClicksRestartNothingDragOrbits viewer_input_test.sh 400)

# Typing into the panel's fields through xdotool (skipped without it).
whisker_viewer_script_test(ViewerInput.TypingAppliesOnEnterFiresNoShortcutUndoRedo viewer_typing_test.sh 400)

# Save writes the image as shown (exposure set by typing) under a free name.
whisker_viewer_script_test(ViewerInput.SaveWritesWhatTheWindowShowsUnderAFreeName viewer_save_test.sh 400)

# The camera stops at the wall; quick key presses all count.
whisker_viewer_script_test(ViewerInput.WheelStaysInTheRoomNoKeyPressLost viewer_room_test.sh 300)

# In the A/B wipe, Save writes both halves as the window shows them and names
# the folder.
whisker_viewer_script_test(ViewerInput.WipeSaveIsTheScreenBothHalvesAndNamesTheFolder viewer_wipe_test.sh 300)

# The pixel readout says "1 sample" / "N samples" and stays over the image;
# the title and the panel say the same samples per pixel in every frame.
whisker_viewer_script_test(ViewerInput.ReadoutStaysOverTheImageTitleAgreesWithPanel viewer_readout_window_test.sh 300)

# After Save scene nothing is left to discard: loading asks nothing; after a
# further edit it asks.
whisker_viewer_script_test(ViewerInput.SaveSceneLeavesNothingToDiscardAFurtherEditAsks viewer_scene_save_test.sh 300)

# A new user's walk on the cat: orbit, wheel, light, glass, Fresnel,
# indirect, depth, undo, redo, save, Esc; a sane image after every step.
whisker_viewer_script_test(ViewerInput.NewUserWalkOnTheCatStaysSane viewer_walk_test.sh 300)

# Esc closes an open dropdown or question before it quits; with unsaved
# edits quitting asks, and Enter says yes.
whisker_viewer_script_test(ViewerInput.EscClosesPopupsQuitAsksAfterEdits viewer_quit_test.sh 300)

# A small window keeps the image (the panel narrows, steps aside, Tab);
# the readout leaves the centre and I hides it; tooltips wait for a rest.
whisker_viewer_script_test(ViewerInput.SmallWindowKeepsTheImageReadoutHidesTooltipsWait viewer_small_window_test.sh 400)

# The Scene dropdown names a loaded file; a saved EXR records the glass-mesh
# edit and the exposure that maps it to the report's display.
whisker_viewer_script_test(ViewerInput.DropdownNamesTheFileExrRecordsEditsAndExposure viewer_scene_file_test.sh 300)

# Sampling > stop at: a render stops after its seconds or at its noise, and
# the render after an edit runs (and stops) again.
whisker_viewer_script_test(ViewerInput.StopAtTimeOrNoiseStopsThisRenderNotTheNext viewer_stop_test.sh 300)
