# Hard cases for the numerics (tests/hard_cases/hard_cases.py): each case
# renders small scenes with the real program and checks an invariance, a
# closed form or a double-precision reference.
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(WHISKER_HARD_CASES offset scale small-far thin-shell tiny-ball light-on-surface light-exactly-on-surface far-obj
    intensity denormals closed-mesh degenerate-mesh extreme-glass huge-mesh glass-far
    subdivided-cat light-in-cage noise-free-error vertex-normals reuse-scale)
foreach(c IN LISTS WHISKER_HARD_CASES)
  add_test(NAME HardCase.${c}
    COMMAND Python3::Interpreter ${CMAKE_CURRENT_SOURCE_DIR}/hard_cases/hard_cases.py
            --whisker $<TARGET_FILE:whisker> --case ${c})
  set_tests_properties(HardCase.${c} PROPERTIES LABELS hard_case TIMEOUT 600)
endforeach()
