# The browser build's libraries (included by the top-level CMakeLists.txt under emcmake).
# scripts/web.sh builds Box2D, yaml-cpp, fuzzylite, zlib and FreeType from Debian's source
# packages with emcc and installs them into FORMSIM_WEB_DEPS; Eigen is header only (Debian's
# headers); Dear ImGui is compiled here from Debian's source (FORMSIM_WEB_IMGUI_SRC). The targets
# carry the names the desktop build's find_package calls give, so the library lists stay one.
set(FORMSIM_WEB_DEPS "" CACHE PATH "Prefix of the libraries scripts/web.sh built with emcc")
set(FORMSIM_WEB_IMGUI_SRC "" CACHE PATH "Debian's imgui source package, unpacked")
if(NOT EXISTS "${FORMSIM_WEB_DEPS}/lib/libbox2d.a")
  message(FATAL_ERROR "FORMSIM_WEB_DEPS='${FORMSIM_WEB_DEPS}' holds no libbox2d.a: run scripts/web.sh")
endif()

# formsim_web_import(TARGET LIB): a static library of FORMSIM_WEB_DEPS as an imported target.
function(formsim_web_import target lib)
  add_library(${target} STATIC IMPORTED GLOBAL)
  set_target_properties(${target} PROPERTIES IMPORTED_LOCATION "${FORMSIM_WEB_DEPS}/lib/${lib}"
                        INTERFACE_INCLUDE_DIRECTORIES "${FORMSIM_WEB_DEPS}/include")
endfunction()
formsim_web_import(box2d::box2d libbox2d.a)
formsim_web_import(yaml-cpp libyaml-cpp.a)
formsim_web_import(formsim_fuzzylite libfuzzylite-static.a)
formsim_web_import(ZLIB::ZLIB libz.a)
formsim_web_import(formsim_freetype libfreetype.a)
set_property(TARGET formsim_freetype APPEND PROPERTY INTERFACE_INCLUDE_DIRECTORIES
             "${FORMSIM_WEB_DEPS}/include/freetype2")

# Eigen: Debian's headers (header only; nothing host-specific in them).
add_library(Eigen3::Eigen INTERFACE IMPORTED GLOBAL)
set_target_properties(Eigen3::Eigen PROPERTIES INTERFACE_INCLUDE_DIRECTORIES /usr/include/eigen3)

# {fmt}: Debian's headers, header only (FMT_HEADER_ONLY), through a folder holding just them (the
# rest of /usr/include is the host's C library, not emscripten's).
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/fmt_include)
file(CREATE_LINK /usr/include/fmt ${CMAKE_BINARY_DIR}/fmt_include/fmt SYMBOLIC)
add_library(fmt::fmt-header-only INTERFACE IMPORTED GLOBAL)
set_target_properties(fmt::fmt-header-only PROPERTIES
                      INTERFACE_INCLUDE_DIRECTORIES ${CMAKE_BINARY_DIR}/fmt_include
                      INTERFACE_COMPILE_DEFINITIONS FMT_HEADER_ONLY=1)

# No threads in the page (a pthread build needs cross-origin isolation, which a page opened
# from a USB stick or a plain web server does not have): one thread, as `--threads 1`.
add_library(Threads::Threads INTERFACE IMPORTED GLOBAL)
add_library(formsim_nlopt INTERFACE)  # tune (NLopt) stays in the CLI: sim/study/tune.cpp is out

# Sources the page does not build (formsim_area_library drops them): tune's optimiser.
set(FORMSIM_WEB_EXCLUDE ${PROJECT_SOURCE_DIR}/sim/study/tune.cpp)
