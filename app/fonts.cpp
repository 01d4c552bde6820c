#include "app/fonts.hpp"

#include <imgui.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

namespace formsim::app {
namespace {

Fonts g_fonts;

std::string FindFont(const std::string& name) {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("FORMSIM_ASSETS")) dirs.push_back(std::string(env) + "/fonts");
  dirs.push_back(std::string(FORMSIM_SOURCE_DIR) + "/assets/fonts");
  dirs.push_back("/usr/share/fonts/truetype/dejavu");
  for (const auto& d : dirs) {
    const std::string path = d + "/" + name;
    if (std::filesystem::is_regular_file(path)) return path;
  }
  return "";
}

// Basic Latin + Latin-1 (°, ², ×), Greek, general punctuation (–, …), super/subscripts (⁻¹),
// arrows and math operators (−, ≈, ≤). Kept alive for the atlas' lifetime.
const ImWchar* GlyphRanges() {
  static const ImWchar ranges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2010, 0x205E, 0x2070, 0x209F,
                                   0x2190, 0x21FF, 0x2200, 0x22FF, 0x25A0, 0x25FF, 0};
  return ranges;
}

}  // namespace

Fonts LoadFonts() {
  ImGuiIO& io = ImGui::GetIO();
  Fonts f;
  const std::string regular = FindFont("DejaVuSans.ttf");
  std::string bold = FindFont("DejaVuSans-Bold.ttf");
  if (bold.empty()) bold = regular;
  std::string mono = FindFont("DejaVuSansMono.ttf");
  if (mono.empty()) mono = regular;
  if (regular.empty()) {
    std::fprintf(stderr,
                 "formsim: warning: DejaVuSans.ttf not found (install fonts-dejavu-core); using "
                 "ImGui's default font, Greek letters will not render\n");
    ImFont* def = io.Fonts->AddFontDefault();
    f.ui = f.small = f.label = f.title = f.mono = def;
    f.source = "ImGui default";
  } else {
    ImFontConfig cfg;
    cfg.OversampleH = 2;  // crisper small text
    cfg.OversampleV = 1;
    cfg.PixelSnapH = false;
    f.ui = io.Fonts->AddFontFromFileTTF(regular.c_str(), 15.0f, &cfg, GlyphRanges());
    f.small = io.Fonts->AddFontFromFileTTF(regular.c_str(), 14.0f, &cfg, GlyphRanges());
    f.label = io.Fonts->AddFontFromFileTTF(regular.c_str(), 16.0f, &cfg, GlyphRanges());
    f.title = io.Fonts->AddFontFromFileTTF(bold.c_str(), 17.0f, &cfg, GlyphRanges());
    f.mono = io.Fonts->AddFontFromFileTTF(mono.c_str(), 14.0f, &cfg, GlyphRanges());
    f.source = regular;
  }
  io.FontDefault = f.ui;
  g_fonts = f;
  return f;
}

const Fonts& CurrentFonts() {
  return g_fonts;
}

}  // namespace formsim::app
