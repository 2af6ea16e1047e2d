# Sanitizer builds: -DWHISKER_SANITIZE=address  (ASan + UBSan, LeakSanitizer on)
#                   -DWHISKER_SANITIZE=thread   (TSan)
# Applied to everything built after this file is included (core, app, tests).
# UBSan findings abort (-fno-sanitize-recover=all) so a test that trips one
# fails instead of printing a line nobody reads. Use a separate build folder
# per sanitizer (build-asan, build-tsan; see CMakePresets.json).
set(WHISKER_SANITIZE "" CACHE STRING "Sanitizer build: '', 'address' (ASan+UBSan) or 'thread' (TSan)")
set_property(CACHE WHISKER_SANITIZE PROPERTY STRINGS "" address thread)

if(WHISKER_SANITIZE STREQUAL "address")
  set(_whisker_san -fsanitize=address,undefined -fno-sanitize-recover=all)
elseif(WHISKER_SANITIZE STREQUAL "thread")
  set(_whisker_san -fsanitize=thread)
elseif(NOT WHISKER_SANITIZE STREQUAL "")
  message(FATAL_ERROR "WHISKER_SANITIZE must be empty, 'address' or 'thread' (got '${WHISKER_SANITIZE}')")
endif()

if(DEFINED _whisker_san)
  # -g1: line tables are all a sanitizer report needs, and compile faster than -g.
  # -O1 (after the build type's -O2, so it wins): the instrumented build
  # compiles in about 2/3 of the time, and ASan's own guide suggests it.
  add_compile_options(${_whisker_san} -fno-omit-frame-pointer -g1 -O1)
  add_link_options(${_whisker_san})
  # Suppression files for third-party noise, found by the tests' environment
  # (scripts/test.sh --sanitize sets the *SAN_OPTIONS that point at them).
  set(WHISKER_SANITIZER_SUPPRESSIONS ${CMAKE_CURRENT_LIST_DIR}/../tests/sanitizers)
  message(STATUS "Whisker: sanitizer build (${WHISKER_SANITIZE})")
endif()
