/// \file The world-view window of the interface: view updates (auto-fit, follow), drawing, and
/// the mouse: wheel zoom, right/middle-drag pan, left-drag of robots and obstacles while paused.
#include <algorithm>
#include <cmath>

#include "app/gui/compare_panel.hpp"
#include "app/gui/timeline_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/render/imgui_canvas.hpp"
#include "app/render/long_text.hpp"
#include "app/render/world_view.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {

void AppUi::UpdateView(ImVec2 min, ImVec2 max) {
  View& v = state_.view;
  v.min = min, v.max = max;
  const sim::Experiment& exp = ShownExperiment();  // the timeline's time, or the live end
  Vec2 lo, hi;
  exp.Bounds(lo, hi);
  auto_fit_.set_mode(state_.whole_run ? AutoFit::Mode::kGrow : AutoFit::Mode::kTrack);
  if ((state_.present || state_.frame_formation) && state_.follow < 0) {
    // Presentation (or "frame the formation"): the camera frames the robots and recent trails.
    if (state_.fit_now) state_.camera.Fit();
    state_.fit_now = false;
    // In presentation mode the buttons cover the top right: the formation is framed below them.
    const float inset = state_.present ? std::max(0.0f, state_.present_bar_bottom - min.y) : 0.0f;
    state_.camera.Update(v, frame_focus_, 0.15, inset);
  } else if (state_.fit_now) {
    if (!state_.whole_run) auto_fit_.Reset();
    state_.auto_fit = true;
    state_.fit_now = false;
    auto_fit_.Update(v, lo, hi, 1.0);
  } else if (state_.auto_fit) {
    auto_fit_.Update(v, lo, hi, 0.15);
  }
  const auto& robots = exp.world().robots();
  if (state_.follow >= 0 && state_.follow < static_cast<int>(robots.size()))
    v.center = robots[state_.follow]->pose().p();
}

const sim::Experiment& AppUi::ShownExperiment() const {
  const sim::Experiment* replayed = timeline_->Shown();  // the timeline's time, else live
  return replayed != nullptr ? *replayed : session_->exp();
}

void AppUi::TrackBounds() {
  if (!state_.whole_run) return;
  Vec2 lo, hi;
  session_->exp().Bounds(lo, hi);
  auto_fit_.Include(lo, hi);
}

void AppUi::DrawWorldMouse(const View& view) {
  ImGuiIO& io = ImGui::GetIO();
  const bool hovered = ImGui::IsItemHovered();
  sim::Experiment& exp = session_->exp();
  if (hovered && io.MouseWheel != 0) {
    state_.view.ZoomAt(io.MousePos, std::pow(1.15, io.MouseWheel));
    state_.auto_fit = false;
    state_.camera.Suspend();  // until fit
  }
  if (ImGui::IsItemActive() && (ImGui::IsMouseDragging(ImGuiMouseButton_Right) ||
                                ImGui::IsMouseDragging(ImGuiMouseButton_Middle))) {
    state_.view.Pan(io.MouseDelta);
    state_.auto_fit = false;
    state_.camera.Suspend();
    state_.follow = -1;
  }
  // The formation editor takes left clicks while it is on (after the legend toggle).
  // A click on the legend's title collapses or opens it (a view setting, not an edit).
  const LegendState& ls = state_.legend_state;
  const bool on_legend = hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left) &&
                         io.MousePos.x >= ls.toggle_min.x && io.MousePos.x <= ls.toggle_max.x &&
                         io.MousePos.y >= ls.toggle_min.y && io.MousePos.y <= ls.toggle_max.y;
  if (on_legend) {
    state_.legend_state.collapsed = !state_.legend_state.collapsed;
    state_.drag_name.clear();
  } else if (kind_panel_ && kind_panel_->WorldMouse(view)) {
    state_.drag_name.clear();
  } else if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    // Picking: the nearest robot (or obstacle centre) within a few pixels of its outline.
    state_.drag_name.clear();
    const Vec2 m = view.ToWorld(io.MousePos);
    double best = 1e300;
    for (const auto& r : exp.world().robots()) {
      const double reach = std::max(r->def().half_length, r->def().radius) + 8.0 / view.scale;
      const double d = (r->pose().p() - m).Norm();
      if (d < reach && d < best) best = d, state_.drag_name = r->name();
    }
    if (state_.drag_name.empty()) {
      for (const auto& o : exp.world().obstacles()) {
        if (o.shape == sim::ObstacleDef::Shape::kWall) continue;
        const double reach =
            (o.shape == sim::ObstacleDef::Shape::kCircle ? o.radius
                                                         : std::max(o.half_x, o.half_y)) +
            4.0 / view.scale;
        const double d = (o.pose.p() - m).Norm();
        if (d < reach && d < best) best = d, state_.drag_name = o.name;
      }
    }
    if (!state_.drag_name.empty() && state_.playing)
      SetStatus("pause (space) to drag " + state_.drag_name);
  }
  if (!state_.drag_name.empty() && ImGui::IsMouseDown(ImGuiMouseButton_Left) && !state_.playing &&
      ImGui::IsMouseDragging(ImGuiMouseButton_Left, 2.0f)) {
    const Vec2 p = view.ToWorld(io.MousePos);
    session_->Move(state_.drag_name, p.x, p.y);
    SetStatus("moved " + state_.drag_name);
  }
  if (ImGui::IsMouseReleased(ImGuiMouseButton_Left)) state_.drag_name.clear();
  if (hovered) {
    const Vec2 m = view.ToWorld(io.MousePos);
    const std::string readout = sim::Sprintf("x %.3f m, y %.3f m", m.x, m.y);
    const ImVec2 ext = ImGui::CalcTextSize(readout.c_str());
    const ImVec2 at = CoordinateReadoutPos(view, ext, world_report_.scale_bar_box,
                                           state_.legend ? world_report_.legend_box : ImVec4());
    // On the theme's backdrop, as the view's labels are: readable over grid lines and trails.
    const Theme& th = GetTheme(state_.theme);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(ImVec2(at.x - 3, at.y - 1), ImVec2(at.x + ext.x + 3, at.y + ext.y + 1),
                      ToImColor(th.backdrop.WithAlpha(0.85f)), 2.0f);
    dl->AddText(at, ToImColor(th.text), readout.c_str());
  }
}

float AppUi::WorldWindowChrome() const { return ImGui::GetFrameHeight() + 8; }

void AppUi::DrawWorldWindow(ImVec2 pos, ImVec2 size, const Fonts& fonts, bool interactive) {
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  const std::string title = Shorten(session_->exp().setup().name, 200) + "###world";
  // No title bar: the view names the scenario under its time, and keeps the height.
  ImGui::Begin(title.c_str(), nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse |
                   ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoBackground);  // the world view paints it
  const ImVec2 min = ImGui::GetCursorScreenPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  // The timeline takes a strip at the bottom.
  const float strip = WorldWindowChrome();
  const ImVec2 max(min.x + std::max(avail.x, 10.0f), min.y + std::max(avail.y - strip, 10.0f));
  // The robots, once a frame for the camera and the world view, and of their recent trails what
  // is needed: every point when the legend chooses its corner (once a second), their box while
  // the camera frames them, else nothing.
  const bool camera = (state_.present || state_.frame_formation) && state_.follow < 0;
  const FocusTrails trails =
      state_.legend && LegendCornerDue(&state_.legend_state, ImGui::GetTime())
          ? FocusTrails::kPoints
      : camera ? FocusTrails::kBox
               : FocusTrails::kNone;
  FocusOf(ShownExperiment(), kFocusTrailSeconds, &frame_focus_, trails);
  UpdateView(min, max);
  world_rect_ = ImVec4(min.x, min.y, max.x, max.y);
  ImGui::InvisibleButton("world", ImVec2(max.x - min.x, max.y - min.y),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                             ImGuiButtonFlags_MouseButtonMiddle);
  WorldViewOptions opt;
  opt.grid = state_.grid;
  opt.coordinates = state_.coordinates;
  opt.scene_overlays = &state_.overlays;
  opt.legend = state_.legend;
  opt.legend_state = &state_.legend_state;
  opt.clock = ImGui::GetTime();
  opt.degrees = state_.settings.degrees;
  opt.report = &world_report_;
  opt.caption = Shorten(session_->exp().setup().name, 80);
  if (state_.present && state_.present_bar.z > state_.present_bar.x) opt.keep_clear.push_back(state_.present_bar);
  opt.focus = &frame_focus_;
  opt.level_of_detail = true;
  compare_->AddWorldOverlays(opt);  // the pins, faded
  const sim::Experiment& shown = ShownExperiment();
  if (&shown != &session_->exp()) {
    opt.time_note = sim::Sprintf("(timeline; live end %.2f s)", session_->exp().time());
  }
  ImGuiCanvas canvas(ImGui::GetWindowDrawList(), fonts);
  canvas.SetWholePixelLines(opt.level_of_detail);
  DrawWorldView(canvas, state_.view, shown, GetTheme(state_.theme), opt);
  // The kind panel's marks (the formation editor's picks).
  if (kind_panel_) kind_panel_->DrawOverWorld(shown, state_.view);
  // A refused change is said over the world view too (presentation mode has no panels).
  constexpr double kRefusalSeconds = 10.0;
  if (state_.status_is_error && !state_.status.empty() &&
      ImGui::GetTime() - state_.status_time < kRefusalSeconds) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float wrap = std::max(100.0f, max.x - min.x - 40);
    const ImVec2 ext = ImGui::CalcTextSize(state_.status.c_str(), nullptr, false, wrap);
    const ImVec2 at(min.x + 12, min.y + 60);
    dl->AddRectFilled(ImVec2(at.x - 6, at.y - 4), ImVec2(at.x + ext.x + 6, at.y + ext.y + 4),
                      ToImColor({1.0f, 0.93f, 0.93f, 0.95f}), 4.0f);
    dl->AddText(nullptr, 0.0f, at, ToImColor({0.75f, 0.05f, 0.05f, 1}), state_.status.c_str(),
                nullptr, wrap);
  }
  // Drags move the live run's bodies: not while the timeline shows another time.
  if (interactive && &shown == &session_->exp()) DrawWorldMouse(state_.view);
  timeline_->Place(ImVec2(min.x, max.y), ImVec2(max.x, max.y + strip));
  timeline_->Draw(fonts);
  ImGui::End();
  ImGui::PopStyleVar();
}

}  // namespace formsim::app
