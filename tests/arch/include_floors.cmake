# The direction of dependencies (docs/architecture.md), checked on every #include:
#   control knows nothing of sim or app; sim knows nothing of app;
#   sim's shared floors: core <- scenario <- session, study; the kinds (sim/<kind>) sit above all four;
#   app's own layers: render <- export <- gui <- cli, each including only the folders to its
#   left: app/render (canvas, plots, themes, GL, the offscreen renderer) knows nothing of export,
#   the window or the CLI; app/export (figures, writers, frame export) nothing of the window or
#   the CLI (it draws the interface through its UiFrames interface); app/gui nothing of the CLI
#   (the stop signal both use is sim/core's); app/web is an outer shell and may use them all;
#   the Python module (python/) uses sim and app/export's in-memory pictures only: no window,
#   GL, ImGui or CLI header (app/export/pictures.hpp hides them).
# Run: cmake -DSOURCE_DIR=<repo> -P include_floors.cmake. Fails listing every offending line.
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "SOURCE_DIR not set")
endif()

# The kinds are the folders sim/<kind> holding a <kind>_experiment.cpp, as in the root CMakeLists.
file(GLOB _sim_dirs LIST_DIRECTORIES true ${SOURCE_DIR}/sim/*)
set(_kinds)
foreach(_dir ${_sim_dirs})
  get_filename_component(_k ${_dir} NAME)
  if(IS_DIRECTORY ${_dir} AND EXISTS ${_dir}/${_k}_experiment.cpp)
    list(APPEND _kinds ${_k})
  endif()
endforeach()
if(NOT _kinds)
  message(FATAL_ERROR "no experiment kinds found under ${SOURCE_DIR}/sim")
endif()
list(JOIN _kinds "|" _kind_alt)

# Pairs: folder, then the include prefixes it must not use (a regex).
set(_rules
  "control;sim|app"
  "sim;app"
  "sim/core;sim/(scenario|session|study|${_kind_alt})/"
  "sim/scenario;sim/(session|study|${_kind_alt})/"
  "sim/session;sim/(study|${_kind_alt})/"
  "sim/study;sim/(session|${_kind_alt})/"
  "app/render;app/(gui|export|cli)/"
  "app/export;app/(gui|cli)/"
  "app/gui;app/cli/"
  "python;app/(render|gui|cli|backends)/|app/export/([a-oq-z]|p[^i])")

set(_bad)
set(_checked 0)
list(LENGTH _rules _n)
math(EXPR _last "${_n} - 1")
foreach(_i RANGE 0 ${_last} 2)
  math(EXPR _j "${_i} + 1")
  list(GET _rules ${_i} _folder)
  list(GET _rules ${_j} _forbidden)
  file(GLOB_RECURSE _files ${SOURCE_DIR}/${_folder}/*.hpp ${SOURCE_DIR}/${_folder}/*.cpp)
  if(NOT _files)
    message(FATAL_ERROR "rule for ${_folder}: no sources found")
  endif()
  foreach(_f ${_files})
    math(EXPR _checked "${_checked} + 1")
    file(STRINGS ${_f} _lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"(${_forbidden})")
    foreach(_l ${_lines})
      file(RELATIVE_PATH _rel ${SOURCE_DIR} ${_f})
      list(APPEND _bad "${_rel}: ${_l}   (${_folder} must not include ${_forbidden})")
    endforeach()
  endforeach()
endforeach()
if(_bad)
  list(JOIN _bad "\n" _text)
  message(FATAL_ERROR "includes against the direction of dependencies:\n${_text}")
endif()
message(STATUS "include floors hold over ${_checked} file checks (kinds: ${_kinds})")
