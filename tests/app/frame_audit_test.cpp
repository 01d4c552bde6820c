// The layout report measures what a person sees (issue 46 item 3). Each defect a lecturer met
// is rebuilt here as a frame, and the audit must name it with its text; the frame without the
// defect must come out clean:
// - a label cut at a window's edge without "…" (the scenario path, a combo's preview);
// - text over text (the pointer's coordinates over the legend's "+2 more");
// - text over a robot, and the legend's box over a robot (presentation mode covered R6);
// - text under 18 px at UI scale 2;
// - grey text on a light or blue ground (#999 on #dbdbdb: 2.06:1);
// - a plot squashed to 50 px by its legend (Compare at scale 2), or upside down;
// - the world view's share of the window.
// Wrapped text breaks at spaces only: a number never splits across lines.
#include "app/gui/frame_audit.hpp"

#include <gtest/gtest.h>
#include <imgui.h>

#include <functional>
#include <string>

#include "app/render/imgui_layer.hpp"
#include "app/render/long_text.hpp"
#include "app/render/offscreen_context.hpp"

namespace formsim::app {
namespace {

constexpr int kW = 640, kH = 480;

// Two frames (the first lays windows out) of `draw`, audited after Render with `marks`.
FrameAudit AuditFrames(const std::function<void()>& draw, AuditMarks marks = {}) {
  OffscreenContext ctx(kW, kH);
  ImGuiLayer layer;
  FrameAudit out;
  for (int frame = 0; frame < 2; ++frame) {
    layer.NewHeadlessFrame(kW, kH, 1.0f / 60.0f);
    draw();
    ImGui::Render();
    marks.display = ImVec2(kW, kH);
    marks.pixel_scale = ImGui::GetIO().DisplayFramebufferScale.x;
    marks.clear_colour = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    out = AuditFrame(*ImGui::GetDrawData(), marks);
  }
  return out;
}

// A fixed window at (x, y) of w x h, no move, no title.
void AuditedWindow(const char* name, float x, float y, float w, float h, const std::function<void()>& items,
            ImGuiWindowFlags extra = 0) {
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, h));
  ImGui::Begin(name, nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoScrollbar | extra);
  items();
  ImGui::End();
}

bool NamesText(const std::vector<AuditFinding>& list, const std::string& text) {
  for (const AuditFinding& f : list)
    if (f.text.find(text) != std::string::npos) return true;
  return false;
}

TEST(FrameAudit, ReadsTheFramesTextBack) {
  const FrameAudit a = AuditFrames([] {
    AuditedWindow("w", 0, 0, 300, 200, [] {
      ImGui::TextUnformatted("achieved 0.99x");
      ImGui::Button("Reset with seed");
    });
  });
  EXPECT_TRUE(NamesText(a.runs, "achieved 0.99x"));
  EXPECT_TRUE(NamesText(a.runs, "Reset with seed"));
  EXPECT_TRUE(a.cut.empty() && a.overlaps.empty() && a.small_text.empty() && a.low_contrast.empty());
}

TEST(FrameAudit, TextCutAtAWindowsEdgeIsFlaggedWithWhatShows) {
  const FrameAudit a = AuditFrames([] {
    AuditedWindow("narrow", 0, 0, 150, 200, [] {
      ImGui::TextUnformatted("/work/main/assets/scenarios/formation_cascade7.yaml");
      ImGui::TextUnformatted("fits");
    });
  });
  ASSERT_EQ(a.cut.size(), 1u);
  EXPECT_EQ(a.cut[0].text.rfind("/work/main/", 0), 0u) << a.cut[0].text;
  EXPECT_EQ(a.cut[0].window, "narrow");
  EXPECT_GT(a.cut[0].rect.z, 140.0f) << "reaches the edge";
}

TEST(FrameAudit, TextWhoseBoxesCrossIsAnOverlapUnlessAFillCoversTheFirst) {
  auto two_texts = [](bool cover) {
    return [cover] {
      AuditedWindow("w", 0, 0, 400, 300, [cover] {
        ImDrawList* dl = ImGui::GetWindowDrawList();
        dl->AddText(ImVec2(50, 100), IM_COL32(0, 0, 0, 255), "+ 2 more (larger view shows them)");
        if (cover) dl->AddRectFilled(ImVec2(40, 90), ImVec2(390, 130), IM_COL32(255, 255, 255, 255));
        dl->AddText(ImVec2(60, 102), IM_COL32(0, 0, 0, 255), "x 2.227 m, y 0.841 m");
      });
    };
  };
  const FrameAudit crossed = AuditFrames(two_texts(false));
  ASSERT_EQ(crossed.overlaps.size(), 1u);
  EXPECT_EQ(crossed.overlaps[0].text, "x 2.227 m, y 0.841 m");
  EXPECT_EQ(crossed.overlaps[0].other, "+ 2 more (larger view shows them)");
  EXPECT_TRUE(AuditFrames(two_texts(true)).overlaps.empty()) << "the first text is hidden, not overlapped";
}

TEST(FrameAudit, TextAndTheLegendOverARobotAreFlaggedByTheRobotsName) {
  AuditMarks marks;
  marks.world_view = ImVec4(0, 0, kW, kH);
  marks.robots.push_back({"R6", ImVec2(200, 200), 20});
  marks.robots.push_back({"R1", ImVec2(500, 400), 20});
  marks.over_world.push_back({"legend", ImVec4(150, 150, 350, 260)});
  const FrameAudit a = AuditFrames(
      [] {
        AuditedWindow("scene###world", 0, 0, kW, kH, [] {
          ImDrawList* dl = ImGui::GetWindowDrawList();
          dl->AddRectFilled(ImVec2(0, 0), ImVec2(kW, kH), IM_COL32(250, 250, 247, 255));
          dl->AddText(ImVec2(160, 195), IM_COL32(0, 0, 0, 255), "trail (path so far)");
          dl->AddText(ImVec2(440, 330), IM_COL32(0, 0, 0, 255), "R1");  // above R1, clear
        });
      },
      marks);
  ASSERT_EQ(a.overlaps.size(), 2u);
  EXPECT_EQ(a.overlaps[0].text, "trail (path so far)");
  EXPECT_EQ(a.overlaps[0].other, "robot R6");
  EXPECT_EQ(a.overlaps[1].text, "legend");
  EXPECT_EQ(a.overlaps[1].other, "robot R6");
}

TEST(FrameAudit, TextUnder18PxIsSmallAtUiScaleTwoOnly) {
  auto text = [] { AuditedWindow("w", 0, 0, 300, 200, [] { ImGui::TextUnformatted("speed"); }); };
  AuditMarks at2;
  at2.ui_scale = 2;
  // The headless layer draws at one pixel per unit: a 15 px font at "scale 2" is too small.
  const FrameAudit a = AuditFrames(text, at2);
  ASSERT_EQ(a.small_text.size(), 1u);
  EXPECT_EQ(a.small_text[0].text, "speed");
  EXPECT_NEAR(a.small_text[0].value, 15.0, 0.6);
  EXPECT_TRUE(AuditFrames(text).small_text.empty()) << "at scale 1 the rule does not apply";
}

TEST(FrameAudit, GreyOnLightGreyIsLowContrastWithItsRatio) {
  auto text = [](ImU32 ink) {
    return [ink] {
      AuditedWindow("w", 0, 0, 300, 200, [ink] {
        ImDrawList* dl = ImGui::GetWindowDrawList();
        dl->AddRectFilled(ImVec2(0, 0), ImVec2(300, 200), IM_COL32(0xdb, 0xdb, 0xdb, 255));
        dl->AddText(ImVec2(10, 10), ink, "playing t = 1.82 s");
      });
    };
  };
  const FrameAudit grey = AuditFrames(text(IM_COL32(0x99, 0x99, 0x99, 255)));
  ASSERT_EQ(grey.low_contrast.size(), 1u);
  EXPECT_NEAR(grey.low_contrast[0].value, 2.06, 0.02);
  EXPECT_EQ(grey.low_contrast[0].other, "#999999 on #dbdbdb");
  EXPECT_TRUE(AuditFrames(text(IM_COL32(0x33, 0x33, 0x33, 255))).low_contrast.empty());
  // Translucent ink is seen over its ground: black at 30% on that grey fails.
  EXPECT_EQ(AuditFrames(text(IM_COL32(0, 0, 0, 77))).low_contrast.size(), 1u);
}

TEST(FrameAudit, SquashedPlotsAreSmallAndTheWorldViewsShareIsMeasured) {
  AuditMarks marks;
  marks.world_view = ImVec4(320, 0, kW, kH);
  marks.plots.push_back({"trajectories", ImVec4(10, 10, 300, 60)});    // 50 px tall
  marks.plots.push_back({"phi_error", ImVec4(10, 200, 300, 190)});     // upside down
  marks.plots.push_back({"distance_error", ImVec4(10, 250, 300, 400)});  // fine
  const FrameAudit a = AuditFrames([] {}, marks);
  ASSERT_EQ(a.small_plots.size(), 2u);
  EXPECT_EQ(a.small_plots[0].text, "trajectories");
  EXPECT_EQ(a.small_plots[0].value, 50.0);
  EXPECT_EQ(a.small_plots[1].value, 0.0);
  EXPECT_DOUBLE_EQ(a.world_view_share, 0.5);
}

TEST(LongTextWrapped, NumbersNeverBreakAcrossLines) {
  const std::string text = "achieved 0.99x; 112 steps of 0.01 s; last frame: 3 steps, sim 0.125 ms, frame 38.125 ms";
  for (float width : {90.0f, 120.0f, 150.0f, 200.0f, 260.0f}) {
    const FrameAudit a = AuditFrames([&] { AuditedWindow("w", 0, 0, width, 400, [&] { LongTextWrapped("t", text); }); });
    std::string joined;
    for (const AuditFinding& r : a.runs) {
      // No line ends in the middle of a number ("0." then "99x").
      ASSERT_FALSE(!r.text.empty() && r.text.back() == '.' && r.text.size() > 1 &&
                   std::isdigit(static_cast<unsigned char>(r.text[r.text.size() - 2])))
          << "width " << width << ": a line ends '" << r.text << "'";
      joined += r.text + " ";
    }
    for (const char* number : {"0.99x;", "0.01", "0.125", "38.125"})
      EXPECT_NE(joined.find(number), std::string::npos) << number << " whole at width " << width;
    EXPECT_TRUE(a.cut.empty()) << "width " << width;
  }
}

}  // namespace
}  // namespace formsim::app
