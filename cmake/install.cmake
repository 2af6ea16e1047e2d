# Where the data lives, the install rules and the Debian package.
#
# The binary finds its data from its own location (/proc/self/exe), never
# from a path compiled in: installed, <prefix>/bin/../share/whisker; in a
# build tree, <build>/assets and <build>/shaders, links to the source's
# folders made here (and <build>/tests/assets, <build>/bench/assets for the
# test and bench binaries that load the bundled scenes).
include(GNUInstallDirs)

foreach(_dir "" tests bench)
  file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/${_dir})
  file(CREATE_LINK ${PROJECT_SOURCE_DIR}/assets ${PROJECT_BINARY_DIR}/${_dir}/assets SYMBOLIC)
endforeach()
file(CREATE_LINK ${PROJECT_SOURCE_DIR}/shaders ${PROJECT_BINARY_DIR}/shaders SYMBOLIC)

# The man page: packaging/whisker.1 with the render settings written in from
# the settings table by the built binary, then compressed as Debian installs
# man pages (-n: no time stamp, so the package is the same for the same
# sources).
set(WHISKER_MAN ${PROJECT_BINARY_DIR}/packaging/whisker.1)
set(WHISKER_MAN_GZ ${WHISKER_MAN}.gz)
add_custom_command(OUTPUT ${WHISKER_MAN} ${WHISKER_MAN_GZ}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/packaging
  COMMAND bash ${PROJECT_SOURCE_DIR}/scripts/update_man.sh $<TARGET_FILE:whisker>
          ${PROJECT_SOURCE_DIR}/packaging/whisker.1 ${WHISKER_MAN}
  COMMAND gzip -9nc ${WHISKER_MAN} > ${WHISKER_MAN_GZ}
  DEPENDS whisker ${PROJECT_SOURCE_DIR}/packaging/whisker.1 ${PROJECT_SOURCE_DIR}/scripts/update_man.sh
  COMMENT "The man page, its settings from the table")
add_custom_target(whisker_man ALL DEPENDS ${WHISKER_MAN_GZ})

set(_data ${CMAKE_INSTALL_DATADIR}/whisker)
install(TARGETS whisker RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY assets/scenes DESTINATION ${_data} FILES_MATCHING PATTERN "*.json")
install(FILES assets/cat.obj DESTINATION ${_data})
if(WHISKER_VIEWER)
  install(DIRECTORY shaders DESTINATION ${_data})
endif()
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
install(FILES ${WHISKER_MAN_GZ} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES packaging/whisker.desktop DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
install(FILES packaging/whisker.png
        DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/256x256/apps)

# --- Debian package: cpack -G DEB in the build folder (scripts/package.sh).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME whisker)
set(CPACK_PACKAGE_VERSION ${WHISKER_VERSION})
set(CPACK_PACKAGE_CONTACT "Whisker developers <whisker@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "progressive CPU path tracer with an OpenGL viewer")
# The package's long description (CPack puts the summary above it).
set(CPACK_PACKAGE_DESCRIPTION
"Whisker renders spheres (diffuse, mirror, glass, hollow glass) and triangle
meshes under a point light with Monte Carlo path tracing. A window shows the
image as it refines; a headless mode writes PNG, PFM and OpenEXR images.
The package includes the bundled scenes and the cat mesh.")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
# Depends: from the shared libraries the binary links (dpkg-shlibdeps).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The viewer needs an OpenGL driver (Mesa's, also for software rendering),
# and `man whisker` a man reader; neither is linked.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libgl1-mesa-dri, man-db")
include(CPack)
