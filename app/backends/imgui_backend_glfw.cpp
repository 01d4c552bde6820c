/// \file Debian's ImGui GLFW platform backend (window, input, clipboard). It makes no GL call.
#include FORMSIM_IMGUI_GLFW_SOURCE
