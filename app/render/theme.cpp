#include "app/render/theme.hpp"

#include "app/render/contrast.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace formsim::app {
namespace {

constexpr sim::Color Rgb(int r, int g, int b, int a = 255) {
  return {r / 255.0f, g / 255.0f, b / 255.0f, a / 255.0f};
}

struct Hsl {
  float h, s, l;
};

Hsl ToHsl(sim::Color c) {
  const float mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b});
  Hsl o{0, 0, 0.5f * (mx + mn)};
  const float d = mx - mn;
  if (d < 1e-6f) return o;
  o.s = o.l > 0.5f ? d / (2 - mx - mn) : d / (mx + mn);
  if (mx == c.r)
    o.h = (c.g - c.b) / d + (c.g < c.b ? 6 : 0);
  else if (mx == c.g)
    o.h = (c.b - c.r) / d + 2;
  else
    o.h = (c.r - c.g) / d + 4;
  o.h /= 6;
  return o;
}

sim::Color FromHsl(Hsl in, float alpha) {
  auto hue = [](float p, float q, float t) {
    if (t < 0) t += 1;
    if (t > 1) t -= 1;
    if (t < 1.0f / 6) return p + (q - p) * 6 * t;
    if (t < 0.5f) return q;
    if (t < 2.0f / 3) return p + (q - p) * (2.0f / 3 - t) * 6;
    return p;
  };
  if (in.s <= 0) return {in.l, in.l, in.l, alpha};
  const float q = in.l < 0.5f ? in.l * (1 + in.s) : in.l + in.s - in.l * in.s, p = 2 * in.l - q;
  return {hue(p, q, in.h + 1.0f / 3), hue(p, q, in.h), hue(p, q, in.h - 1.0f / 3), alpha};
}

Theme MakeLight() {
  Theme t{};
  t.id = ThemeId::kLight;
  t.name = "light";
  t.background = Rgb(250, 250, 247);
  t.text = Rgb(20, 20, 20);
  t.axis = Rgb(40, 40, 40);
  t.grid = Rgb(222, 222, 218);
  t.legend_fill = Rgb(255, 255, 255, 235);
  t.legend_border = Rgb(135, 135, 135);  // 3:1 and more on the background (WCAG)
  t.reference = Rgb(110, 110, 110);
  t.marker = Rgb(200, 40, 40);
  t.cursor = Rgb(60, 60, 60, 160);
  t.error = Rgb(180, 30, 30);
  t.world_minor = Rgb(236, 236, 232);
  t.world_major = Rgb(212, 212, 206);
  t.world_axis = Rgb(138, 138, 133);
  t.coordinates = Rgb(108, 108, 108);  // text: 4.5:1
  t.backdrop = Rgb(255, 255, 255);
  return t;
}

Theme MakeDark() {
  Theme t{};
  t.id = ThemeId::kDark;
  t.name = "dark";
  t.dark = true;
  t.background = Rgb(30, 32, 36);
  t.text = Rgb(228, 228, 228);
  t.axis = Rgb(200, 200, 200);
  t.grid = Rgb(62, 64, 70);
  t.legend_fill = Rgb(40, 42, 48, 235);
  t.legend_border = Rgb(110, 110, 115);
  t.reference = Rgb(160, 160, 160);
  t.marker = Rgb(245, 100, 100);
  t.cursor = Rgb(210, 210, 210, 160);
  t.error = Rgb(255, 120, 120);
  t.world_minor = Rgb(40, 42, 47);
  t.world_major = Rgb(60, 62, 68);
  t.world_axis = Rgb(112, 114, 122);
  t.coordinates = Rgb(150, 150, 150);
  t.backdrop = Rgb(30, 32, 36);
  return t;
}

Theme MakePrint() {
  Theme t{};
  t.id = ThemeId::kPrint;
  t.name = "print";
  t.background = Rgb(255, 255, 255);
  t.text = Rgb(0, 0, 0);
  t.axis = Rgb(0, 0, 0);
  t.grid = Rgb(218, 218, 218);
  t.legend_fill = Rgb(255, 255, 255, 240);
  t.legend_border = Rgb(100, 100, 100);
  t.reference = Rgb(140, 140, 140);
  t.marker = Rgb(0, 0, 0);
  t.cursor = Rgb(60, 60, 60, 160);
  t.error = Rgb(0, 0, 0);
  t.world_minor = Rgb(240, 240, 240);
  t.world_major = Rgb(210, 210, 210);
  t.world_axis = Rgb(140, 140, 140);
  t.coordinates = Rgb(80, 80, 80);
  t.backdrop = Rgb(255, 255, 255);
  return t;
}

Theme MakeHighContrast() {
  Theme t{};
  t.id = ThemeId::kHighContrast;
  t.name = "high-contrast";
  t.dark = true;
  t.line_scale = 2.0f;  // thicker lines, seen from the back of a room
  t.background = Rgb(0, 0, 0);
  t.text = Rgb(255, 255, 255);
  t.axis = Rgb(255, 255, 255);
  t.grid = Rgb(85, 85, 85);
  t.legend_fill = Rgb(0, 0, 0, 235);
  t.legend_border = Rgb(255, 255, 255);
  t.reference = Rgb(210, 210, 210);
  t.marker = Rgb(255, 80, 80);
  t.cursor = Rgb(255, 255, 255, 200);
  t.error = Rgb(255, 90, 90);
  t.world_minor = Rgb(30, 30, 30);
  t.world_major = Rgb(75, 75, 75);
  t.world_axis = Rgb(150, 150, 150);
  t.coordinates = Rgb(230, 230, 230);
  t.backdrop = Rgb(0, 0, 0);
  return t;
}

}  // namespace

// Dark themes keep hues but turn greys around (black outlines and labels become light) and
// lift dark colours so they stand out on the dark background; print keeps only luminance.
static sim::Color MapInk(const Theme& theme, sim::Color c) {
  const ThemeId id = theme.id;
  switch (id) {
    case ThemeId::kLight:
      return c;
    case ThemeId::kPrint: {
      const float y = 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
      const float g = 0.85f * y;  // a little darker: light colours stay visible on paper
      return {g, g, g, c.a};
    }
    case ThemeId::kDark:
    case ThemeId::kHighContrast: {
      Hsl h = ToHsl(c);
      const bool hc = id == ThemeId::kHighContrast;
      const float grey_l = hc ? 1.0f - h.l : 0.92f - 0.8f * h.l;
      const float colour_l = hc ? std::max(0.55f, h.l) : 0.25f + 0.75f * h.l;
      const float w = std::clamp(h.s / 0.25f, 0.0f, 1.0f);
      h.l = (1 - w) * grey_l + w * colour_l;
      if (hc && w > 0) h.s = std::max(h.s, 0.9f);
      return FromHsl(h, c.a);
    }
  }
  return c;
}

// A few distinct colours are asked for many times a frame (a thousand robots): the last ones are
// remembered, as the contrast search costs a few dozen pow() calls.
static sim::Color Remembered(const Theme& theme, sim::Color c, double ratio) {
  struct Slot {
    const Theme* theme = nullptr;
    double ratio = 0;
    sim::Color in, out;
  };
  thread_local Slot slots[16];
  auto same = [](sim::Color a, sim::Color b) {
    return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a;
  };
  const unsigned h = static_cast<unsigned>(c.r * 255) * 7u + static_cast<unsigned>(c.g * 255) * 13u +
                     static_cast<unsigned>(c.b * 255) * 31u + (ratio > 4 ? 1u : 0u);
  Slot& s = slots[h % 16];
  if (s.theme == &theme && s.ratio == ratio && same(s.in, c)) return s.out;
  const sim::Color mapped = MapInk(theme, c);
  sim::Color out = WithContrast(mapped.WithAlpha(1.0f), theme.background, ratio);
  out.a = ratio > kLineContrast ? 1.0f : mapped.a;
  s = {&theme, ratio, c, out};
  return out;
}

sim::Color Theme::Ink(sim::Color c) const {
  return Remembered(*this, c, kLineContrast);
}

sim::Color Theme::Fill(sim::Color c) const {
  return MapInk(*this, c);
}

sim::Color Theme::HeadingInk(sim::Color body) const {
  return sim::HeadingInk(Over(Fill(body), background));
}

sim::Color Theme::TextInk(sim::Color c) const {
  return Remembered(*this, c, kTextContrast);
}

const std::vector<ThemeInk>& ThemeInks() {
  static const std::vector<ThemeInk> k = {
      {"text", &Theme::text, InkUse::kText},
      {"axis", &Theme::axis, InkUse::kText},  // tick labels and the scale bar's text
      {"grid", &Theme::grid, InkUse::kDecoration},
      {"legend_fill", &Theme::legend_fill, InkUse::kDecoration},
      {"legend_border", &Theme::legend_border, InkUse::kLine},
      {"reference", &Theme::reference, InkUse::kLine},
      {"marker", &Theme::marker, InkUse::kLine},
      {"cursor", &Theme::cursor, InkUse::kLine},
      {"error", &Theme::error, InkUse::kText},
      {"world_minor", &Theme::world_minor, InkUse::kDecoration},
      {"world_major", &Theme::world_major, InkUse::kDecoration},
      {"world_axis", &Theme::world_axis, InkUse::kLine},
      {"coordinates", &Theme::coordinates, InkUse::kText},
      {"backdrop", &Theme::backdrop, InkUse::kDecoration},
  };
  return k;
}

SeriesLook Theme::Series(sim::Color color, int index, bool dashed) const {
  SeriesLook look;
  const int i = std::max(0, index);
  if (id != ThemeId::kPrint) {
    look.color = Ink(color);
    if (dashed) look.dash = LineDash::Dashes(8, 5);
    // Past the colour cycle colours repeat: a dash pattern per lap tells the series apart.
    static const LineDash kLapDash[] = {LineDash::Dashes(7, 4), LineDash::Dashes(2, 3),
                                        LineDash::DashDot(9, 3, 2), LineDash::Dashes(14, 5)};
    const int lap = i / kPaletteSize;
    if (lap > 0 && look.dash.solid()) look.dash = kLapDash[(lap - 1) % 4];
    return look;
  }
  // Print: told apart in greyscale by the dash pattern, the marker and the grey level. The
  // cycles have coprime lengths (6, 7, 5), so the (dash, marker) pair first repeats at 42.
  static const float kGrey[] = {0.0f, 0.42f, 0.2f, 0.55f, 0.3f};
  static const LineDash kDash[] = {LineDash::Solid(),       LineDash::Dashes(7, 4),
                                   LineDash::Dashes(2, 3),  LineDash::DashDot(9, 3, 2),
                                   LineDash::Dashes(14, 5), LineDash::DashDot(4, 2, 1)};
  static const MarkerShape kMarker[] = {MarkerShape::kCircle,       MarkerShape::kSquare,
                                        MarkerShape::kTriangle,     MarkerShape::kDiamond,
                                        MarkerShape::kTriangleDown, MarkerShape::kPlus,
                                        MarkerShape::kCross};
  const float g = kGrey[i % 5];
  look.color = {g, g, g, color.a};
  look.dash = kDash[i % 6];
  look.marker = kMarker[i % 7];
  if (dashed && look.dash.solid()) look.dash = LineDash::Dashes(8, 5);
  look.hollow_markers = (i % 2) != 0;
  return look;
}

const Theme& GetTheme(ThemeId id) {
  static const Theme kLight = MakeLight(), kDark = MakeDark(), kPrint = MakePrint(),
                     kHighContrast = MakeHighContrast();
  switch (id) {
    case ThemeId::kLight:
      return kLight;
    case ThemeId::kDark:
      return kDark;
    case ThemeId::kPrint:
      return kPrint;
    case ThemeId::kHighContrast:
      return kHighContrast;
  }
  return kLight;
}

const char* ThemeNames() {
  return "light|dark|print|high-contrast";
}

ThemeId ParseTheme(const std::string& text, const std::string& flag) {
  for (ThemeId id : {ThemeId::kLight, ThemeId::kDark, ThemeId::kPrint, ThemeId::kHighContrast})
    if (text == GetTheme(id).name) return id;
  throw std::runtime_error(flag + " '" + text + "': expected one of " + ThemeNames());
}

// Makes the style meet the text contrast (4.5:1, WCAG 1.4.3) for text, grey text, check marks
// and the edges of checkboxes and radio buttons, on every surface they are drawn on.
static void MeetTextContrast(ImGuiStyle& style);

void ApplyImGuiTheme(const Theme& theme) {
  ImGuiStyle& style = ImGui::GetStyle();
  auto c = [](sim::Color k) { return ImVec4(k.r, k.g, k.b, k.a); };
  if (theme.dark) {
    ImGui::StyleColorsDark();
  } else {
    ImGui::StyleColorsLight();
  }
  // The panels' background is the world view's and the plots' in every theme: their backgrounds
  // are then the window's own clear, and a software rasteriser skips them (clear_hoist.hpp).
  switch (theme.id) {
    case ThemeId::kLight:
      style.Colors[ImGuiCol_WindowBg] = c(theme.background);
      break;
    case ThemeId::kPrint:
      style.Colors[ImGuiCol_WindowBg] = ImVec4(1, 1, 1, 1);
      style.Colors[ImGuiCol_Text] = ImVec4(0, 0, 0, 1);
      break;
    case ThemeId::kDark:
      style.Colors[ImGuiCol_WindowBg] = c(theme.background);
      break;
    case ThemeId::kHighContrast:
      style.Colors[ImGuiCol_WindowBg] = ImVec4(0, 0, 0, 1);
      style.Colors[ImGuiCol_ChildBg] = ImVec4(0, 0, 0, 1);
      style.Colors[ImGuiCol_Text] = ImVec4(1, 1, 1, 1);
      style.Colors[ImGuiCol_TextDisabled] = ImVec4(0.8f, 0.8f, 0.8f, 1);
      style.Colors[ImGuiCol_Border] = ImVec4(1, 1, 1, 0.8f);
      style.Colors[ImGuiCol_FrameBg] = ImVec4(0.15f, 0.15f, 0.15f, 1);
      style.Colors[ImGuiCol_Button] = ImVec4(0.1f, 0.3f, 0.75f, 1);
      style.Colors[ImGuiCol_CheckMark] = ImVec4(1, 0.85f, 0.1f, 1);
      style.Colors[ImGuiCol_SliderGrab] = ImVec4(1, 0.85f, 0.1f, 1);
      break;
  }
  // Slider handles stay translucent: the value's digits, drawn over the handle, keep their
  // contrast wherever it sits (sliders of few steps have wide handles).
  for (ImGuiCol k : {ImGuiCol_SliderGrab, ImGuiCol_SliderGrabActive}) style.Colors[k].w = 0.35f;
  MeetTextContrast(style);
}

static void MeetTextContrast(ImGuiStyle& style) {
  // A little above 4.5:1, so that rounding to 8-bit channels never takes a pair below it.
  constexpr double kRatio = kTextContrast + 0.1;
  auto col = [&](ImGuiCol k) {
    const ImVec4& v = style.Colors[k];
    return sim::Color{v.x, v.y, v.z, v.w};
  };
  auto set = [&](ImGuiCol k, sim::Color c) { style.Colors[k] = ImVec4(c.r, c.g, c.b, c.a); };
  const sim::Color window = Over(col(ImGuiCol_WindowBg), sim::Color{0, 0, 0, 1});
  const std::vector<sim::Color> bases = {window, Over(col(ImGuiCol_PopupBg), window),
                                         Over(col(ImGuiCol_ChildBg), window)};
  const sim::Color text = Over(col(ImGuiCol_Text), window);
  // Every surface text is drawn on (frames, headers, buttons, tabs, table rows) keeps the text
  // readable: one that does not is moved away from the text's colour (its hue kept), opaque.
  static const ImGuiCol kSurfaces[] = {
      ImGuiCol_FrameBg,       ImGuiCol_FrameBgHovered, ImGuiCol_FrameBgActive,
      ImGuiCol_Header,        ImGuiCol_HeaderHovered,  ImGuiCol_HeaderActive,
      ImGuiCol_Button,        ImGuiCol_ButtonHovered,  ImGuiCol_ButtonActive,
      ImGuiCol_Tab,           ImGuiCol_TabHovered,     ImGuiCol_TabActive,
      ImGuiCol_TableHeaderBg, ImGuiCol_TableRowBgAlt,  ImGuiCol_MenuBarBg};
  std::vector<sim::Color> surfaces = bases;
  for (ImGuiCol k : kSurfaces) {
    bool reads = true;
    for (const sim::Color& b : bases) reads = reads && ContrastRatio(text, Over(col(k), b)) >= kRatio;
    if (!reads) set(k, WithContrast(Over(col(k), window), text, kRatio));
    for (const sim::Color& b : bases) surfaces.push_back(Over(col(k), b));
  }
  // Secondary (grey) text reads on every one of them, as text does: "grey on blue" included.
  for (int pass = 0; pass < 2; ++pass)
    for (const sim::Color& bg : surfaces)
      set(ImGuiCol_TextDisabled, WithContrast(Over(col(ImGuiCol_TextDisabled), bg), bg, kRatio));
  // Checkboxes and radio buttons: the mark reads on the box, and the box's edge (drawn, with a
  // frame border of 1) on what is around it.
  for (int pass = 0; pass < 2; ++pass)
    for (ImGuiCol frame : {ImGuiCol_FrameBg, ImGuiCol_FrameBgHovered, ImGuiCol_FrameBgActive})
      for (const sim::Color& b : bases) {
        const sim::Color bg = Over(col(frame), b);
        set(ImGuiCol_CheckMark, WithContrast(Over(col(ImGuiCol_CheckMark), bg), bg, kRatio));
      }
  for (int pass = 0; pass < 2; ++pass)
    for (const sim::Color& b : bases)
      set(ImGuiCol_Border, WithContrast(Over(col(ImGuiCol_Border), b), b, kRatio));
  style.FrameBorderSize = std::max(style.FrameBorderSize, 1.0f);
}

}  // namespace formsim::app
