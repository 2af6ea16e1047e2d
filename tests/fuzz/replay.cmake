# The fuzz corpus and the reproducers of past findings as ordinary tests, in
# every build (Release, ASan + UBSan, TSan): the harnesses linked with a
# plain main() instead of libFuzzer. Included from tests/CMakeLists.txt.
set(WHISKER_FUZZ_DIR ${CMAKE_CURRENT_LIST_DIR})
foreach(name scene obj)
  add_executable(fuzz_${name}_replay ${WHISKER_FUZZ_DIR}/fuzz_${name}.cpp ${WHISKER_FUZZ_DIR}/replay_main.cpp)
  target_link_libraries(fuzz_${name}_replay PRIVATE whisker_core)
endforeach()

add_test(NAME Fuzz.SceneCorpusAndReproducers COMMAND fuzz_scene_replay
  ${WHISKER_FUZZ_DIR}/corpus/scene ${WHISKER_FUZZ_DIR}/reproducers/scene)
add_test(NAME Fuzz.ObjCorpusAndReproducers COMMAND fuzz_obj_replay
  ${WHISKER_FUZZ_DIR}/corpus/obj ${WHISKER_FUZZ_DIR}/reproducers/obj)
set_tests_properties(Fuzz.SceneCorpusAndReproducers Fuzz.ObjCorpusAndReproducers
  PROPERTIES ENVIRONMENT WHISKER_FUZZ_STRICT=1 LABELS fuzz)

# Findings not yet mended, run strictly (no tolerance): enabled with the fix.
add_test(NAME Fuzz.ObjPendingReproducers COMMAND fuzz_obj_replay ${WHISKER_FUZZ_DIR}/reproducers/pending/obj)
set_tests_properties(Fuzz.ObjPendingReproducers PROPERTIES
  ENVIRONMENT WHISKER_FUZZ_STRICT=1 LABELS fuzz
  # A mtllib name over 255 bytes: std::filesystem::exists throws
  # filesystem_error out of load_obj (uncaught, exit 134) instead of MeshError.
  DISABLED TRUE)
