# The fuzz corpus and the reproducers of past findings as ordinary tests, in
# every build (Release, ASan + UBSan, TSan): the harnesses linked with a
# plain main() instead of libFuzzer. Included from tests/CMakeLists.txt.
set(WHISKER_FUZZ_DIR ${CMAKE_CURRENT_LIST_DIR})
foreach(name scene obj part)
  add_executable(fuzz_${name}_replay ${WHISKER_FUZZ_DIR}/fuzz_${name}.cpp ${WHISKER_FUZZ_DIR}/replay_main.cpp)
  target_link_libraries(fuzz_${name}_replay PRIVATE whisker_core)
endforeach()

add_test(NAME Fuzz.SceneCorpusAndReproducers COMMAND fuzz_scene_replay
  ${WHISKER_FUZZ_DIR}/corpus/scene ${WHISKER_FUZZ_DIR}/reproducers/scene)
add_test(NAME Fuzz.ObjCorpusAndReproducers COMMAND fuzz_obj_replay
  ${WHISKER_FUZZ_DIR}/corpus/obj ${WHISKER_FUZZ_DIR}/reproducers/obj)
# The part (accumulation EXR) reader: merge and resume read files from anywhere.
add_test(NAME Fuzz.PartCorpusAndReproducers COMMAND fuzz_part_replay
  ${WHISKER_FUZZ_DIR}/corpus/part ${WHISKER_FUZZ_DIR}/reproducers/part)
set_tests_properties(Fuzz.SceneCorpusAndReproducers Fuzz.ObjCorpusAndReproducers Fuzz.PartCorpusAndReproducers
  PROPERTIES ENVIRONMENT WHISKER_FUZZ_STRICT=1 LABELS fuzz)

# A finding not yet mended goes to reproducers/pending/<harness>/ with a
# test of its own registered DISABLED here (run strictly, no tolerance),
# and moves to reproducers/<harness>/ with its fix. None is pending now.
