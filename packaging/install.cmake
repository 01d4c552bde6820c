# Install rules of formsim (cmake --install build --prefix P), included by the top CMakeLists.txt.
# Everything lands under the prefix, nothing points back at the source tree: the program finds
# share/formsim beside itself (sim/scenario/asset_dirs.hpp), so a moved prefix still works.
#
#   bin/formsim
#   share/formsim/{scenarios,lessons,fuzzy,fonts}
#   share/applications/formsim.desktop                    opens `formsim gui`
#   share/icons/hicolor/{scalable,256x256}/apps/formsim.{svg,png}   drawn by `formsim icon`
#   share/metainfo/io.github.formsim.metainfo.xml         AppStream
#   share/man/man1/formsim.1.gz                           from `formsim reference --format man`
#   share/bash-completion/completions/formsim             from `formsim reference --format bash`
#   share/doc/formsim/{README.md,CHANGELOG.md.gz,changelog.gz,copyright}
#   the Python module (python/CMakeLists.txt): Debian's python3 dist-packages under the prefix
include(GNUInstallDirs)
set(FORMSIM_RELEASE_DATE 2026-12-06 CACHE STRING "The release date of this version (AppStream, changelog)")
set(_gen ${PROJECT_BINARY_DIR}/generated)
file(MAKE_DIRECTORY ${_gen})

install(TARGETS formsim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/assets/scenarios ${PROJECT_SOURCE_DIR}/assets/lessons
                  ${PROJECT_SOURCE_DIR}/assets/fuzzy ${PROJECT_SOURCE_DIR}/assets/fonts
        DESTINATION ${CMAKE_INSTALL_DATADIR}/formsim)

# Made by the program just built, from its own definitions: they cannot drift from --help. A
# sanitizer build's program reports the GL driver's never-freed allocations at exit: no leak
# check here (the tests check leaks).
set(_run ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=0 $<TARGET_FILE:formsim>)
add_custom_command(
  OUTPUT ${_gen}/formsim.1 ${_gen}/formsim.1.gz ${_gen}/formsim.bash-completion
  COMMAND ${_run} reference --format man > ${_gen}/formsim.1
  COMMAND gzip -9nc ${_gen}/formsim.1 > ${_gen}/formsim.1.gz
  COMMAND ${_run} reference --format bash > ${_gen}/formsim.bash-completion
  DEPENDS formsim COMMENT "formsim.1 and the bash completion from the CLI definitions" VERBATIM)
add_custom_command(
  OUTPUT ${_gen}/formsim.svg ${_gen}/formsim.png
  COMMAND ${_run} icon --svg ${_gen}/formsim.svg --png ${_gen}/formsim.png --png-size 256
  DEPENDS formsim COMMENT "the icon, drawn by formsim" VERBATIM)
configure_file(${CMAKE_CURRENT_LIST_DIR}/io.github.formsim.metainfo.xml.in
               ${_gen}/io.github.formsim.metainfo.xml @ONLY)
configure_file(${CMAKE_CURRENT_LIST_DIR}/changelog.Debian.in ${_gen}/changelog @ONLY)
add_custom_command(
  OUTPUT ${_gen}/changelog.gz ${_gen}/CHANGELOG.md.gz
  COMMAND gzip -9nc ${_gen}/changelog > ${_gen}/changelog.gz
  COMMAND gzip -9nc ${PROJECT_SOURCE_DIR}/CHANGELOG.md > ${_gen}/CHANGELOG.md.gz
  DEPENDS ${_gen}/changelog ${PROJECT_SOURCE_DIR}/CHANGELOG.md VERBATIM)
add_custom_target(formsim_install_files ALL
  DEPENDS ${_gen}/formsim.1.gz ${_gen}/formsim.bash-completion ${_gen}/formsim.svg
          ${_gen}/formsim.png ${_gen}/changelog.gz ${_gen}/CHANGELOG.md.gz)

install(FILES ${_gen}/formsim.1.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${_gen}/formsim.bash-completion DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
        RENAME formsim)
install(FILES ${CMAKE_CURRENT_LIST_DIR}/formsim.desktop DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
install(FILES ${_gen}/formsim.svg DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps)
install(FILES ${_gen}/formsim.png DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/256x256/apps)
install(FILES ${_gen}/io.github.formsim.metainfo.xml DESTINATION ${CMAKE_INSTALL_DATADIR}/metainfo)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${_gen}/CHANGELOG.md.gz ${_gen}/changelog.gz
              ${CMAKE_CURRENT_LIST_DIR}/copyright
        DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/formsim)

include(${CMAKE_CURRENT_LIST_DIR}/cpack.cmake)
