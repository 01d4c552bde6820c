#include "app/render/fonts.hpp"

#include <imgui.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "sim/scenario/asset_dirs.hpp"

namespace formsim::app {
namespace {

Fonts g_fonts;

}  // namespace

const FontSpec& FontSpecOf(FontRole role) {
  static const FontSpec kUi{"DejaVuSans.ttf", "DejaVu Sans", false, 15.0f};
  static const FontSpec kSmall{"DejaVuSans.ttf", "DejaVu Sans", false, 14.0f};
  static const FontSpec kLabel{"DejaVuSans.ttf", "DejaVu Sans", false, 16.0f};
  static const FontSpec kTitle{"DejaVuSans-Bold.ttf", "DejaVu Sans", true, 17.0f};
  static const FontSpec kMono{"DejaVuSansMono.ttf", "DejaVu Sans Mono", false, 14.0f};
  switch (role) {
    case FontRole::kUi:
      return kUi;
    case FontRole::kSmall:
      return kSmall;
    case FontRole::kLabel:
      return kLabel;
    case FontRole::kTitle:
      return kTitle;
    case FontRole::kMono:
      return kMono;
  }
  return kUi;
}

std::string FindFont(const std::string& name) {
  std::vector<std::string> dirs;
  dirs.push_back(sim::AssetDir("fonts"));
  dirs.push_back("/usr/share/fonts/truetype/dejavu");
  for (const auto& d : dirs) {
    const std::string path = d + "/" + name;
    if (std::filesystem::is_regular_file(path)) return path;
  }
  return "";
}

// Basic Latin + Latin-1 (°, ², ×), Greek, general punctuation (–, …), super/subscripts (⁻¹),
// arrows and math operators (−, ≈, ≤). Kept alive for the atlas' lifetime.
const ImWchar* FontGlyphRanges() {
  static const ImWchar ranges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2010, 0x205E, 0x2070, 0x209F,
                                   0x2190, 0x21FF, 0x2200, 0x22FF, 0x25A0, 0x25FF, 0};
  return ranges;
}

ImFont* Fonts::Get(FontRole role) const {
  switch (role) {
    case FontRole::kUi:
      return ui;
    case FontRole::kSmall:
      return small;
    case FontRole::kLabel:
      return label;
    case FontRole::kTitle:
      return title;
    case FontRole::kMono:
      return mono;
  }
  return ui;
}

Fonts LoadFonts(float scale) {
  ImGuiIO& io = ImGui::GetIO();
  Fonts f;
  f.scale = scale;
  const std::string regular = FindFont(FontSpecOf(FontRole::kUi).file);
  if (regular.empty()) {
    std::fputs(
        "formsim: warning: DejaVuSans.ttf not found (install fonts-dejavu-core); using "
        "ImGui's default font, Greek letters will not render\n",
        stderr);
    ImFontConfig cfg;
    cfg.SizePixels = 13.0f * scale;
    ImFont* def = io.Fonts->AddFontDefault(&cfg);
    f.ui = f.small = f.label = f.title = f.mono = def;
    f.source = "ImGui default";
  } else {
    ImFontConfig cfg;
    cfg.OversampleH = 2;  // crisper small text
    cfg.OversampleV = 1;
    cfg.PixelSnapH = false;
    auto add = [&](FontRole role) {
      const FontSpec& spec = FontSpecOf(role);
      std::string file = FindFont(spec.file);
      if (file.empty()) file = regular;  // bold or mono missing: the regular face
      return io.Fonts->AddFontFromFileTTF(file.c_str(), spec.pixels * scale, &cfg,
                                          FontGlyphRanges());
    };
    f.ui = add(FontRole::kUi);
    f.small = add(FontRole::kSmall);
    f.label = add(FontRole::kLabel);
    f.title = add(FontRole::kTitle);
    f.mono = add(FontRole::kMono);
    f.source = regular;
  }
  io.FontDefault = f.ui;
  // Widgets draw text at FontSize * FontGlobalScale: the logical size.
  io.FontGlobalScale = 1.0f / scale;
  g_fonts = f;
  return f;
}

const Fonts& CurrentFonts() {
  return g_fonts;
}

}  // namespace formsim::app
