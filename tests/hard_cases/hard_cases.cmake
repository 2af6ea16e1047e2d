# Hard cases for the numerics (tests/hard_cases/hard_cases.py): each case
# renders small scenes with the real program and checks an invariance, a
# closed form or a double-precision reference.
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(WHISKER_HARD_CASES offset scale small-far thin-shell tiny-ball light-on-surface light-exactly-on-surface far-obj
    intensity denormals closed-mesh degenerate-mesh extreme-glass huge-mesh glass-far
    subdivided-cat light-in-cage noise-free-error vertex-normals)
foreach(c IN LISTS WHISKER_HARD_CASES)
  add_test(NAME HardCase.${c}
    COMMAND Python3::Interpreter ${CMAKE_CURRENT_SOURCE_DIR}/hard_cases/hard_cases.py
            --whisker $<TARGET_FILE:whisker> --case ${c})
  set_tests_properties(HardCase.${c} PROPERTIES LABELS hard_case TIMEOUT 600)
  # Under ASan the hard cases' renders run without the fake stacks that find
  # a use of a stack frame after its function returned (1.7x the time of a
  # render): the same render code runs with them in the Progressive.*,
  # LightConnect.* and Headless.* tests, and the hard cases are here for
  # the numbers' out-of-bounds reads and undefined behaviour.
  if(WHISKER_SANITIZE STREQUAL "address")
    set_tests_properties(HardCase.${c} PROPERTIES ENVIRONMENT_MODIFICATION
      "ASAN_OPTIONS=string_append::detect_stack_use_after_return=0")
  endif()
endforeach()
