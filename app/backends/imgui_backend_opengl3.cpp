/// \file Debian's ImGui OpenGL3 backend, compiled with a custom loader: every GL call in it goes
/// through the function pointers of imgui_impl_opengl3_loader.h, which app/render/gl_api.cpp loads for
/// the current context (GLFW window or OSMesa) with imgl3wInit2(). IMGUI_IMPL_OPENGL_LOADER_CUSTOM
/// is defined by CMake; the backend then includes no GL header, so we include the loader first.
#include "imgui_impl_opengl3_loader.h"
#include FORMSIM_IMGUI_GL3_SOURCE
