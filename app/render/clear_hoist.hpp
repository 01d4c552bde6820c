#pragma once
/// \file The frame's first background clear done as the frame's own clear. A software
/// rasteriser (llvmpipe) clears a whole framebuffer almost for free but draws a scissored clear
/// as a quad over its pixels: a world view filling the window cost ~3 ms a frame at 1920x1080.
/// When nothing drawn before that background reaches its rectangle, the framebuffer is cleared to
/// the background's colour and only the strips around it to the frame's colour: every pixel ends
/// as it would have. Then every other background clear that would write the colour its rectangle
/// already has (a plot's background in a window of the same colour), with nothing drawn into it
/// before, is skipped.

#include <imgui.h>

namespace formsim::app {

/// Clears the framebuffer of `fb_width` x `fb_height` pixels for `dd`: to the first background
/// clear's colour, with the strips around it to (r, g, b), when nothing before that clear draws
/// into its rectangle and the strips cover at most half of its area; that clear then does nothing
/// in `dd`. Otherwise clears all of it to (r, g, b), as GlClear. Then turns into nothing each
/// background clear whose colour is already the whole of its rectangle's, and nothing before it
/// draws there. Returns whether it hoisted; `skipped` gets the number of clears left out
/// (the hoisted one included).
bool ClearForFrame(ImDrawData& dd, int fb_width, int fb_height, float r, float g, float b,
                   int* skipped);

}  // namespace formsim::app
