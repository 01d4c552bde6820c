#pragma once
/// \file The few GL entry points formsim calls itself, loaded per context through a
/// get-proc-address function (glfwGetProcAddress or OSMesaGetProcAddress). No GL header here:
/// libOSMesa exports every gl* symbol, so a direct call would bind to OSMesa even in a window.

#include <cstdint>
#include <string>
#include <vector>

namespace formsim::app {

using GlProc = void (*)();
using GlGetProcAddress = GlProc (*)(const char*);

/// Loads the ImGui backend's GL pointers (imgl3wInit2) and ours for the current context.
/// Throws std::runtime_error when the context is not OpenGL 3.x or a pointer is missing.
void LoadGl(GlGetProcAddress get_proc, const char* context_name);

/// The current context's GL_RENDERER and GL_VERSION: "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL
/// 4.5 (Core Profile) Mesa 22.3.6" (formsim doctor).
std::string GlRendererText();
/// Sets the viewport to the framebuffer and clears all of it (scissor test off) with an sRGB
/// colour in [0, 1].
void GlClear(int width, int height, float r, float g, float b);
/// Clears the rectangle of `width` x `height` pixels whose bottom-left corner is (x, y) (GL's
/// window coordinates) to `rgba` (ImGui's packed colour), with the scissor test on. The next
/// draw sets its own scissor.
void GlClearRect(int x, int y, int width, int height, std::uint32_t rgba);
/// The same with the colour as four channels in [0, 1].
void GlClearRect(int x, int y, int width, int height, float r, float g, float b, float a);
/// Turns the scissor test off (after GlClearRect outside the backend's draws).
void GlScissorOff();
/// Waits until every GL command has finished (the OSMesa buffer is then complete).
void GlFinish();
/// Hands every GL command issued so far to the GL to carry out, without waiting for them
/// (llvmpipe rasterises on its own threads meanwhile).
void GlFlush();
/// Reads the current framebuffer as RGBA, top row first.
std::vector<std::uint8_t> GlReadRgba(int width, int height);

}  // namespace formsim::app
