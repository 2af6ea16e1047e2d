# Install and package tests (included from tests/CMakeLists.txt): the
# installed tree with the source tree hidden, the scene lookup order, the
# Debian package, the desktop entry, the man page, the installed viewer.
set(_dir ${CMAKE_CURRENT_SOURCE_DIR}/install)
set(_root ${PROJECT_SOURCE_DIR})

add_test(NAME Install.InstalledTreeRunsWithoutTheSourceTree
  COMMAND bash ${_dir}/install_test.sh ${PROJECT_BINARY_DIR} ${_root} ${WHISKER_VERSION}
          ${WHISKER_VIEWER})
add_test(NAME Install.SceneNameLookupOrderAndFileArgument
  COMMAND bash ${_dir}/scene_lookup_test.sh $<TARGET_FILE:whisker> ${_root})
add_test(NAME Install.DebianPackageFilesDependsVersion
  COMMAND bash ${_dir}/deb_test.sh ${PROJECT_BINARY_DIR} ${_root} ${WHISKER_VERSION})
add_test(NAME Install.DesktopEntryValidates
  COMMAND bash ${_dir}/desktop_test.sh ${_root})
add_test(NAME Install.ManPageNamesEveryHelpOption
  COMMAND bash ${_dir}/man_test.sh $<TARGET_FILE:whisker> ${PROJECT_BINARY_DIR}/packaging/whisker.1)
set_tests_properties(Install.InstalledTreeRunsWithoutTheSourceTree
  Install.SceneNameLookupOrderAndFileArgument Install.DebianPackageFilesDependsVersion
  Install.DesktopEntryValidates Install.ManPageNamesEveryHelpOption
  PROPERTIES TIMEOUT 300 LABELS install)
if(WHISKER_VIEWER)
  add_test(NAME Install.ViewerFromInstalledTreeScreenshot
    COMMAND bash ${_dir}/viewer_test.sh ${PROJECT_BINARY_DIR} ${_root})
  set_tests_properties(Install.ViewerFromInstalledTreeScreenshot PROPERTIES
    SKIP_RETURN_CODE 77 TIMEOUT 300 RESOURCE_LOCK whisker_xvfb LABELS "install;viewer")
endif()
