# Fault tests of the headless command line (tests/faults/cli_faults.sh), one
# ctest test per case. Exit 77 = skipped (not root, no tmpfs, no OpenEXR),
# with the reason printed. Included from tests/CMakeLists.txt.
set(WHISKER_FAULT_CASES
  sigint-render-writes-passes-so-far sigkill-render-leaves-nothing
  sigint-mid-write-cleans-up sigkill-mid-write-never-partial
  disk-full-png disk-full-pfm disk-full-exr disk-full-stats
  readonly-folder special-fifo-targets special-device-target
  float-options-refuse-nan mesh-filesystem-errors
  sigterm-render-writes-passes-so-far disk-full-sum disk-full-checkpoint disk-full-merge
  special-targets-every-option long-output-names
  outputs-never-clobber-inputs signal-while-loading scene-device-files huge-polygon
  messages-one-line empty-option-values
  sighup-render-writes-passes-so-far sigpipe-reader-gone outputs-never-clobber-scene-meshes
  mesh-option-needs-meshes output-extensions scene-duplicate-keys camera-up-degenerate
  non-utf8-names obj-bad-normals accumulation-damaged-header checkpoint-warns-once
  input-slips thread-creation-fails stop-within-a-long-pass temp-files-unpredictable
  closed-standard-descriptors memory-bounds part-contents-checked part-features-checked
  scene-parse-linear scene-nesting-capped messages-escaped list-options-one-reader
  obj-memory-bounded)
foreach(c ${WHISKER_FAULT_CASES})
  add_test(NAME Faults.${c}
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/cli_faults.sh $<TARGET_FILE:whisker> ${c})
  set_tests_properties(Faults.${c} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120 LABELS faults)
endforeach()
# Signals as job wrappers send them (tests/faults/signal_faults.sh).
foreach(c wrapper-signal-copies-one-request under-timeout second-request-stops-at-once
          same-signal-later-is-a-second-request)
  add_test(NAME Faults.${c}
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/signal_faults.sh $<TARGET_FILE:whisker> ${c})
  set_tests_properties(Faults.${c} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120 LABELS faults)
endforeach()
# Opening a file: FILE.obj and --mesh, and a screenshot with no room (tests/faults/open_faults.sh).
foreach(c obj-file-never-aborts screenshot-without-room)
  add_test(NAME Faults.${c}
    COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/open_faults.sh $<TARGET_FILE:whisker> ${c})
  set_tests_properties(Faults.${c} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120 LABELS faults)
endforeach()
