/// \file The right-hand window: live plots of the experiment's figures (our plot widget, with a
/// time cursor), its tables (with firing-strength bars) and the summary with events.
#include <algorithm>
#include <cctype>
#include <cmath>

#include "app/figure_data.hpp"
#include "app/imgui_canvas.hpp"
#include "app/ui.hpp"

namespace formsim::app {

void AppUi::DrawPlotsWindow(ImVec2 pos, ImVec2 size, const Fonts& fonts) {
  ImGui::SetNextWindowPos(pos);
  ImGui::SetNextWindowSize(size);
  ImGui::Begin("Plots###plots", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar);
  const sim::Experiment& exp = session_->exp();
  // A tab asked for by a script (`tab history`) comes to the front once.
  auto tab = [&](const char* name) {
    std::string lower = name;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool select = state_.select_tab == lower;
    if (select) state_.select_tab.clear();
    return select ? ImGuiTabItemFlags_SetSelected : ImGuiTabItemFlags_None;
  };
  if (ImGui::BeginTabBar("tabs")) {
    if (ImGui::BeginTabItem("Plots", nullptr, tab("Plots"))) {
      // The figure list can change during a run (an estimator switched on adds its figure), so
      // the user's choices are kept by figure id.
      const auto figures = exp.Figures();
      auto is_open = [&](const sim::FigureSpec& f) {
        const auto it = state_.plot_closed.find(f.id);
        return it == state_.plot_closed.end() || !it->second;
      };
      // Toggles for each figure, then the open ones stacked (scrolling when they do not fit).
      for (std::size_t i = 0; i < figures.size(); ++i) {
        if (i > 0) ImGui::SameLine();
        bool open = is_open(figures[i]);
        const std::string id = figures[i].id + "##toggle";
        if (ImGui::Checkbox(id.c_str(), &open)) state_.plot_closed[figures[i].id] = !open;
        if (ImGui::GetContentRegionAvail().x < 120 && i + 1 < figures.size()) ImGui::NewLine();
      }
      ImGui::BeginChild("plot_list", ImVec2(0, 0), false);
      int open_count = 0;
      for (const auto& f : figures) open_count += is_open(f);
      const float avail_h = ImGui::GetContentRegionAvail().y;
      const float h = std::max(220.0f, open_count > 0 ? avail_h / std::min(open_count, 3) - 6 : 0);
      PlotStyle style;
      style.title_font = FontRole::kLabel;
      style.label_font = FontRole::kUi;
      style.tick_font = FontRole::kSmall;
      style.line_width = 1.6f;
      style.padding = 6;
      style.theme = &GetTheme(state_.theme);
      ImGuiCanvas canvas(ImGui::GetWindowDrawList(), fonts);
      for (std::size_t i = 0; i < figures.size(); ++i) {
        if (!is_open(figures[i])) continue;
        const ImVec2 p0 = ImGui::GetCursorScreenPos();
        const float w = ImGui::GetContentRegionAvail().x;
        ImGui::Dummy(ImVec2(w, h));
        if (!ImGui::IsItemVisible()) continue;  // scrolled away: skip the work
        PlotData data = ResolveFigure(figures[i], exp.recorder());
        DecoratePlot(figures[i], data);  // pinned runs, Monte Carlo bands
        const PlotLayout L = DrawPlot(canvas, p0, ImVec2(p0.x + w, p0.y + h), data, style,
                                      data.x_is_time ? CursorTime() : std::nan(""));
        // Hovering shows each series' value under the mouse.
        if (ImGui::IsItemHovered() && !data.equal_aspect) {
          const ImVec2 m = ImGui::GetIO().MousePos;
          if (m.x >= L.area_min.x && m.x <= L.area_max.x) {
            const double x =
                L.x0 + (m.x - L.area_min.x) / (L.area_max.x - L.area_min.x) * (L.x1 - L.x0);
            ImGui::BeginTooltip();
            ImGui::Text("%s = %.4g", data.x_label.c_str(), x);
            for (const auto& s : data.series) {
              const double y = SampleSeries(s, x);
              if (std::isfinite(y) && !s.label.empty()) {
                const sim::Color c = style.theme->Series(s.color, s.style_index, s.dashed).color;
                ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1), "%s: %.5g", s.label.c_str(), y);
              }
            }
            ImGui::EndTooltip();
          }
        }
      }
      ImGui::EndChild();
      ImGui::EndTabItem();
    }
    // The results as tables (the same metrics as summary.json), then the experiment's own.
    const sim::Metrics results = exp.Results();
    std::vector<sim::TableSpec> tables = results.GuiTables();
    for (auto& t : exp.Tables()) tables.push_back(std::move(t));
    if (!tables.empty() && ImGui::BeginTabItem("Tables", nullptr, tab("Tables"))) {
      DrawCompareTable(results);
      for (std::size_t t = 0; t < tables.size(); ++t) {
        const sim::TableSpec& spec = tables[t];
        ImGui::TextUnformatted(spec.title.c_str());
        const int cols = static_cast<int>(spec.header.size()) + (spec.row_strength.empty() ? 0 : 1);
        if (cols == 0) continue;
        ImGui::PushID(static_cast<int>(t));
        if (ImGui::BeginTable("tbl", cols,
                              ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                  ImGuiTableFlags_SizingStretchProp)) {
          for (const auto& h : spec.header) ImGui::TableSetupColumn(h.c_str());
          if (!spec.row_strength.empty()) ImGui::TableSetupColumn("strength");
          ImGui::TableHeadersRow();
          for (std::size_t r = 0; r < spec.rows.size(); ++r) {
            ImGui::TableNextRow();
            for (std::size_t c = 0; c < spec.header.size(); ++c) {
              ImGui::TableSetColumnIndex(static_cast<int>(c));
              if (c < spec.rows[r].size()) ImGui::TextUnformatted(spec.rows[r][c].c_str());
            }
            if (!spec.row_strength.empty()) {
              ImGui::TableSetColumnIndex(static_cast<int>(spec.header.size()));
              const double s = r < spec.row_strength.size() ? spec.row_strength[r] : 0.0;
              ImGui::ProgressBar(
                  static_cast<float>(std::clamp(std::isfinite(s) ? s : 0.0, 0.0, 1.0)),
                  ImVec2(-1, 0));
            }
          }
          ImGui::EndTable();
        }
        ImGui::PopID();
        ImGui::Spacing();
      }
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("History", nullptr, tab("History"))) {
      DrawHistoryTab();
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Summary", nullptr, tab("Summary"))) {
      ImGui::PushFont(fonts.mono);
      ImGui::TextUnformatted(exp.SummaryText().c_str());
      ImGui::PopFont();
      ImGui::Separator();
      const auto& events = exp.events().list();
      ImGui::Text("%zu events", events.size());
      for (const auto& e : events)
        ImGui::TextWrapped("%.2f s  %s  %s: %s", e.time, e.kind.c_str(), e.robots.c_str(),
                           e.message.c_str());
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
}

}  // namespace formsim::app
