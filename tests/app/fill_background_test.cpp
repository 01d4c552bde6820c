// A world view's background is cleared (a scissored glClear in a draw callback) instead of
// shaded as a quad, for software GL (issue 24 item 9). The pixels must be the ones the quad gave:
// rendered both ways, with a clip rectangle cutting the background, in every theme colour, with
// lines and text drawn over it, at UI scale 1 and 2.
#include <gtest/gtest.h>
#include <imgui.h>

#include <cstdint>
#include <vector>

#include "app/render/gl_api.hpp"
#include "app/render/imgui_canvas.hpp"
#include "app/render/imgui_layer.hpp"
#include "app/render/offscreen_context.hpp"
#include "app/render/theme.hpp"

namespace formsim::app {
namespace {

std::vector<std::uint8_t> Render(ImGuiLayer& layer, int w, int h, float scale, bool clear,
                                 sim::Color bg, int* callbacks) {
  layer.NewHeadlessFrame(w, h, 1.0f / 60.0f);
  ImGui::Begin("v", nullptr, ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoDecoration);
  ImGui::End();
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  ImGuiCanvas cv(dl, layer.fonts());
  cv.SetClearBackgrounds(clear);
  cv.FillRect(ImVec2(0, 0), ImVec2(400, 300), sim::Color{0.9f, 0.9f, 0.9f, 1}, 0);
  // Whole pixels, clipped on the right and the bottom by the canvas clip.
  cv.PushClip(ImVec2(20, 10), ImVec2(300, 250));
  cv.FillBackground(ImVec2(10, 20), ImVec2(380, 290), bg);
  cv.Line(ImVec2(0, 0), ImVec2(400, 300), Stroke(sim::Color{0.1f, 0.3f, 0.8f, 1}, 2.5f));
  cv.Text(ImVec2(40, 40), FontRole::kLabel, sim::Color{0, 0, 0, 1}, "R1 l 0.300 m");
  cv.FillRect(ImVec2(100, 100), ImVec2(160, 140), sim::Color{1, 0.5f, 0, 0.5f}, 4);
  cv.PopClip();
  // Not on whole pixels: drawn as a quad either way.
  cv.FillBackground(ImVec2(310.5f, 20.25f), ImVec2(390, 120), bg);
  *callbacks = 0;
  for (const ImDrawCmd& cmd : dl->CmdBuffer) *callbacks += cmd.UserCallback != nullptr;
  const int fw = static_cast<int>(w * scale), fh = static_cast<int>(h * scale);
  layer.Render(fw, fh, 0.2f, 0.2f, 0.2f);
  return GlReadRgba(fw, fh);
}

TEST(FillBackground, ClearGivesTheQuadsPixels) {
  for (const float scale : {1.0f, 2.0f}) {
    const int w = 400, h = 300;
    OffscreenContext ctx(static_cast<int>(w * scale), static_cast<int>(h * scale));
    ImGuiLayer layer;
    if (scale != 1.0f) layer.SetFontScale(scale);
    for (const char* name : {"light", "dark", "print", "high-contrast"}) {
      const sim::Color bg = GetTheme(ParseTheme(name)).background;
      int quad_clears = -1, clears = -1;
      const auto quad = Render(layer, w, h, scale, false, bg, &quad_clears);
      const auto cleared = Render(layer, w, h, scale, true, bg, &clears);
      EXPECT_EQ(quad_clears, 0);
      EXPECT_EQ(clears, 1) << "the whole-pixel background is a clear, the other a quad";
      ASSERT_EQ(quad.size(), cleared.size());
      std::size_t differ = 0;
      for (std::size_t i = 0; i < quad.size(); ++i) differ += quad[i] != cleared[i];
      EXPECT_EQ(differ, 0u) << name << " at scale " << scale;
      // The background is there (not the frame's clear colour) inside the clip.
      const std::size_t at =
          (static_cast<std::size_t>(200 * scale) * static_cast<std::size_t>(w * scale) +
           static_cast<std::size_t>(250 * scale)) *
          4;
      EXPECT_EQ(cleared[at], static_cast<std::uint8_t>(bg.r * 255 + 0.5f)) << name;
    }
  }
}

// The frame's first background clear done as the frame's clear (clear_hoist.hpp): the pixels of
// the frame cleared first and the background cleared over it, whether or not it applies.
struct HoistCase {
  const char* what;
  ImVec2 before_min, before_max;  // drawn before the background (a bar, or something under it)
  ImVec2 bg_min, bg_max;          // the background
  bool hoisted;                   // whether the hoist applies
};

std::vector<std::uint8_t> RenderHoist(ImGuiLayer& layer, int w, int h, float scale, bool hoist,
                                      const HoistCase& c, sim::Color bg, bool* hoisted) {
  layer.NewHeadlessFrame(w, h, 1.0f / 60.0f);
  ImGui::Begin("v", nullptr, ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoDecoration);
  ImGui::End();
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  ImGuiCanvas cv(dl, layer.fonts());
  // A bar with text and an anti-aliased rule along its bottom (as the menu bar).
  if (c.before_max.x > c.before_min.x) {
    cv.FillRect(c.before_min, c.before_max, sim::Color{0.95f, 0.95f, 0.95f, 1}, 0);
    cv.Line(ImVec2(c.before_min.x, c.before_max.y - 1.5f),
            ImVec2(c.before_max.x, c.before_max.y - 1.5f),
            Stroke(sim::Color{0.2f, 0.2f, 0.2f, 1}, 1.0f));
    cv.Text(ImVec2(c.before_min.x + 4, c.before_min.y + 2), FontRole::kSmall,
            sim::Color{0, 0, 0, 1}, "File Run View");
  }
  cv.PushClip(c.bg_min, c.bg_max);
  cv.FillBackground(c.bg_min, c.bg_max, bg);
  cv.Line(ImVec2(0, 0), ImVec2(400, 300), Stroke(sim::Color{0.1f, 0.3f, 0.8f, 1}, 2.5f));
  cv.Text(ImVec2(60, 80), FontRole::kLabel, sim::Color{0, 0, 0, 1}, "R1 l 0.300 m");
  cv.PopClip();
  const int fw = static_cast<int>(w * scale), fh = static_cast<int>(h * scale);
  layer.SetHoistClears(hoist);
  layer.Render(fw, fh, 0.2f, 0.25f, 0.3f);
  *hoisted = layer.hoisted_clear();
  return GlReadRgba(fw, fh);
}

TEST(FillBackground, FrameClearedToTheFirstBackgroundGivesTheSamePixels) {
  const int w = 400, h = 300;
  const HoistCase cases[] = {
      {"a view under a bar, a pixel from each side", ImVec2(0, 0), ImVec2(400, 21), ImVec2(1, 21),
       ImVec2(399, 299), true},
      {"the view is the whole frame", ImVec2(0, 0), ImVec2(0, 0), ImVec2(0, 0), ImVec2(400, 300),
       true},
      {"the bar reaches one row into the view", ImVec2(0, 0), ImVec2(400, 22), ImVec2(1, 21),
       ImVec2(399, 299), false},
      {"the bar's line reaches into the view", ImVec2(0, 0), ImVec2(400, 21.5f), ImVec2(0, 21),
       ImVec2(400, 300), false},
      {"a small view: the strips around it would cost more", ImVec2(0, 0), ImVec2(400, 21),
       ImVec2(100, 100), ImVec2(200, 200), false},
  };
  for (const float scale : {1.0f, 2.0f}) {
    OffscreenContext ctx(static_cast<int>(w * scale), static_cast<int>(h * scale));
    ImGuiLayer layer;
    if (scale != 1.0f) layer.SetFontScale(scale);
    for (const char* name : {"light", "high-contrast"}) {
      const sim::Color bg = GetTheme(ParseTheme(name)).background;
      for (const HoistCase& c : cases) {
        bool off_hoisted = true, on_hoisted = false;
        const auto plain = RenderHoist(layer, w, h, scale, false, c, bg, &off_hoisted);
        const auto hoisted = RenderHoist(layer, w, h, scale, true, c, bg, &on_hoisted);
        EXPECT_FALSE(off_hoisted);
        EXPECT_EQ(on_hoisted, c.hoisted) << c.what << " at scale " << scale;
        ASSERT_EQ(plain.size(), hoisted.size());
        std::size_t differ = 0;
        for (std::size_t i = 0; i < plain.size(); ++i) differ += plain[i] != hoisted[i];
        EXPECT_EQ(differ, 0u) << c.what << ", " << name << " at scale " << scale;
      }
    }
  }
}

// A background clear that would write the colour already under it (a plot's background in a
// window of that colour) is left out: the same pixels, and only where nothing drawn before it
// reaches its rectangle and its whole rectangle has that one colour.
struct SkipCase {
  const char* what;
  bool view;  // a view background (the hoisted one) first, over most of the frame
  ImVec2 plot_min, plot_max;
  bool plot_of_frame;  // the plot's colour: the frame's (else the view's colour)
  bool line_before;    // a line drawn before the plot, crossing into it
  bool other_before;   // a background of another colour over part of the plot, before it
  int skipped;         // clears left out, the hoisted one included
};

std::vector<std::uint8_t> RenderSkip(ImGuiLayer& layer, int w, int h, float scale, bool skip,
                                     const SkipCase& c, int* skipped) {
  const sim::Color frame{51 / 255.0f, 64 / 255.0f, 77 / 255.0f, 1};
  const sim::Color view{250 / 255.0f, 250 / 255.0f, 247 / 255.0f, 1};
  layer.NewHeadlessFrame(w, h, 1.0f / 60.0f);
  ImGui::Begin("v", nullptr, ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoDecoration);
  ImGui::End();
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  ImGuiCanvas cv(dl, layer.fonts());
  if (c.view) {
    cv.PushClip(ImVec2(0, 20), ImVec2(360, 300));
    cv.FillBackground(ImVec2(0, 20), ImVec2(360, 300), view);
    cv.Text(ImVec2(20, 30), FontRole::kLabel, sim::Color{0, 0, 0, 1}, "t = 1.00 s");
    cv.PopClip();
  }
  if (c.line_before)
    cv.Line(ImVec2(0, 0), ImVec2(400, 300), Stroke(sim::Color{0.1f, 0.3f, 0.8f, 1}, 2.0f));
  if (c.other_before) cv.FillBackground(ImVec2(100, 100), ImVec2(240, 160), sim::Color{1, 1, 1, 1});
  cv.PushClip(c.plot_min, c.plot_max);
  cv.FillBackground(c.plot_min, c.plot_max, c.plot_of_frame ? frame : view);
  cv.Line(ImVec2(c.plot_min.x, c.plot_max.y), c.plot_max,
          Stroke(sim::Color{0.8f, 0.2f, 0.1f, 1}, 2.0f));
  cv.Text(ImVec2(c.plot_min.x + 6, c.plot_min.y + 4), FontRole::kSmall, sim::Color{0, 0, 0, 1},
          "(b) e_phi");
  cv.PopClip();
  const int fw = static_cast<int>(w * scale), fh = static_cast<int>(h * scale);
  layer.SetHoistClears(skip);
  layer.Render(fw, fh, frame.r, frame.g, frame.b);
  *skipped = layer.skipped_clears();
  return GlReadRgba(fw, fh);
}

TEST(FillBackground, ClearOfTheColourAlreadyThereIsLeftOutWithTheSamePixels) {
  const int w = 400, h = 300;
  const SkipCase cases[] = {
      {"a plot of the frame's colour", false, ImVec2(200, 40), ImVec2(380, 200), true, false, false,
       1},
      {"a plot of another colour", false, ImVec2(200, 40), ImVec2(380, 200), false, false, false,
       0},
      {"a line drawn before reaches into the plot", false, ImVec2(200, 40), ImVec2(380, 200), true,
       true, false, 0},
      {"a background of another colour before it overlaps the plot", false, ImVec2(200, 40),
       ImVec2(380, 200), true, false, true, 0},
      {"a plot of the view's colour inside the hoisted view", true, ImVec2(180, 60),
       ImVec2(340, 200), false, false, false, 2},
      {"a plot of the frame's colour inside the hoisted view", true, ImVec2(180, 60),
       ImVec2(340, 200), true, false, false, 1},
      {"a plot across the hoisted view's edge", true, ImVec2(300, 60), ImVec2(400, 200), false,
       false, false, 1},
  };
  for (const float scale : {1.0f, 2.0f}) {
    OffscreenContext ctx(static_cast<int>(w * scale), static_cast<int>(h * scale));
    ImGuiLayer layer;
    if (scale != 1.0f) layer.SetFontScale(scale);
    for (const SkipCase& c : cases) {
      int off_skipped = -1, on_skipped = -1;
      const auto plain = RenderSkip(layer, w, h, scale, false, c, &off_skipped);
      const auto skipped = RenderSkip(layer, w, h, scale, true, c, &on_skipped);
      EXPECT_EQ(off_skipped, 0);
      EXPECT_EQ(on_skipped, c.skipped) << c.what << " at scale " << scale;
      ASSERT_EQ(plain.size(), skipped.size());
      std::size_t differ = 0;
      for (std::size_t i = 0; i < plain.size(); ++i) differ += plain[i] != skipped[i];
      EXPECT_EQ(differ, 0u) << c.what << " at scale " << scale;
    }
  }
}

// Every theme's panels have the world view's and the plots' background: their backgrounds are
// then the window's own clear, left out for software GL (above).
TEST(FillBackground, PanelsShareTheViewsBackgroundInEveryTheme) {
  OffscreenContext ctx(64, 64);
  ImGuiLayer layer;
  for (const char* name : {"light", "dark", "print", "high-contrast"}) {
    const Theme& th = GetTheme(ParseTheme(name));
    layer.SetTheme(th);
    const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    EXPECT_EQ(ImGui::ColorConvertFloat4ToU32(bg), ToImColor(th.background)) << name;
  }
}

// Square widget corners: a rounded frame is an anti-aliased fan of about 20 triangles, a square
// one 2, and a software rasteriser pays per triangle (docs/benchmarks.md: the window, fifth round).
TEST(FillBackground, WidgetsHaveSquareCorners) {
  OffscreenContext ctx(64, 64);
  ImGuiLayer layer;
  const ImGuiStyle& st = ImGui::GetStyle();
  for (const float r : {st.WindowRounding, st.ChildRounding, st.PopupRounding, st.FrameRounding,
                        st.GrabRounding, st.ScrollbarRounding, st.TabRounding})
    EXPECT_EQ(r, 0.0f);
}

}  // namespace
}  // namespace formsim::app
