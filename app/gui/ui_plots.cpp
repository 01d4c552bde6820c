/// \file The right-hand window: live plots of the experiment's figures (our plot widget, with a
/// time cursor), its tables (with firing-strength bars) and the summary with events.
///
/// A thousand robots record tens of thousands of columns and thousands of result rows, so
/// nothing here is rebuilt every frame: the figures are resolved against the recorder and drawn
/// at most ten times a second (or when the data or the plot's place change), and the frames in
/// between append the geometry the last drawing produced again (only the time cursor is new);
/// the tables and the summary text are computed at most four times a second, and only while
/// their tab is shown.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>

#include "app/export/figure_data.hpp"
#include "app/gui/command_table.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/gui/history_panel.hpp"
#include "app/gui/lesson_panel.hpp"
#include "app/gui/table_header.hpp"
#include "app/gui/ui.hpp"
#include "app/render/display_unit.hpp"
#include "app/render/imgui_canvas.hpp"
#include "app/render/label_markup.hpp"
#include "app/render/long_text.hpp"
#include "app/render/plot_units.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPlotRefresh = std::chrono::milliseconds(100);
constexpr auto kTableRefresh = std::chrono::milliseconds(250);

// The geometry one DrawPlot call appended to a draw list: its vertices, its indices (relative
// to those vertices) and, per draw command, the clip rectangle, texture and index range.
struct DrawnGeometry {
  struct Cmd {
    ImVec4 clip;
    ImTextureID texture;
    int idx_begin = 0, idx_count = 0;
  };
  std::vector<ImDrawVert> vtx;
  std::vector<int> idx;
  std::vector<Cmd> cmds;
};

struct DrawMark {
  int vtx = 0, idx = 0, cmd = 0;
};
DrawMark Mark(const ImDrawList* dl) { return {dl->VtxBuffer.Size, dl->IdxBuffer.Size, dl->CmdBuffer.Size}; }

// What was appended to `dl` since `m`.
DrawnGeometry Capture(const ImDrawList* dl, DrawMark m) {
  DrawnGeometry g;
  g.vtx.assign(dl->VtxBuffer.Data + m.vtx, dl->VtxBuffer.Data + dl->VtxBuffer.Size);
  for (int c = std::max(0, m.cmd - 1); c < dl->CmdBuffer.Size; ++c) {
    const ImDrawCmd& cmd = dl->CmdBuffer[c];
    const int begin = std::max(static_cast<int>(cmd.IdxOffset), m.idx);
    const int end = static_cast<int>(cmd.IdxOffset + cmd.ElemCount);
    if (end <= begin) continue;
    DrawnGeometry::Cmd out{cmd.ClipRect, cmd.TextureId, static_cast<int>(g.idx.size()), end - begin};
    // Indices count from the command's vertex offset (large meshes): make them relative to
    // the first vertex captured.
    for (int i = begin; i < end; ++i)
      g.idx.push_back(static_cast<int>(cmd.VtxOffset + dl->IdxBuffer[i]) - m.vtx);
    g.cmds.push_back(out);
  }
  return g;
}

// Appends `g` to `dl` again, command by command (each with its vertices, which no other command
// shares).
void Replay(ImDrawList* dl, const DrawnGeometry& g) {
  for (const DrawnGeometry::Cmd& c : g.cmds) {
    int lo = static_cast<int>(g.vtx.size()), hi = -1;
    for (int i = c.idx_begin; i < c.idx_begin + c.idx_count; ++i) {
      lo = std::min(lo, g.idx[i]);
      hi = std::max(hi, g.idx[i]);
    }
    if (hi < lo || lo < 0 || hi >= static_cast<int>(g.vtx.size())) continue;
    const int n_vtx = hi - lo + 1;
    dl->PushClipRect(ImVec2(c.clip.x, c.clip.y), ImVec2(c.clip.z, c.clip.w), false);
    dl->PushTextureID(c.texture);
    dl->PrimReserve(c.idx_count, n_vtx);
    const ImDrawIdx base = static_cast<ImDrawIdx>(dl->_VtxCurrentIdx);
    std::copy(g.vtx.begin() + lo, g.vtx.begin() + hi + 1, dl->_VtxWritePtr);
    for (int i = 0; i < c.idx_count; ++i)
      dl->_IdxWritePtr[i] = static_cast<ImDrawIdx>(base + (g.idx[c.idx_begin + i] - lo));
    dl->_VtxWritePtr += n_vtx;
    dl->_IdxWritePtr += c.idx_count;
    dl->_VtxCurrentIdx += static_cast<unsigned int>(n_vtx);
    dl->PopTextureID();
    dl->PopClipRect();
  }
}

}  // namespace

// One figure as last drawn.
struct CachedPlot {
  PlotData data;
  PlotLayout layout;
  DrawnGeometry geometry;
  ImVec2 p0, p1;
  std::size_t rows = 0;
  Clock::time_point at;
  std::string decoration;  ///< the pins and Monte Carlo bands it was drawn with
  bool valid = false;
};

struct AppUi::PlotsCache {
  // Which run and how far: a change of run (reset, load) or new rows call for a refresh.
  const sim::Experiment* exp = nullptr;
  std::string file, name;
  ThemeId theme = ThemeId::kLight;
  std::size_t rows = 0;
  long steps = -1;
  std::vector<sim::FigureSpec> figures;
  Clock::time_point figures_at;
  std::map<std::string, CachedPlot> plots;
  sim::Metrics results;
  std::vector<sim::TableSpec> tables;
  std::string summary;
  Clock::time_point tables_at, summary_at;
  long tables_steps = -1, summary_steps = -1;
  bool tables_valid = false;
};

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
  if (!plots_cache_) plots_cache_ = std::make_shared<PlotsCache>();
  PlotsCache& cache = *plots_cache_;
  const Clock::time_point now = Clock::now();
  const std::size_t rows = exp.recorder().rows_sampled();
  // A new run (or the same one reset: fewer rows or steps than before) drops everything.
  if (&exp != cache.exp || rows < cache.rows || exp.steps() < cache.steps ||
      exp.setup().file != cache.file || exp.setup().name != cache.name ||
      state_.theme != cache.theme) {
    *plots_cache_ = PlotsCache{};
    cache.theme = state_.theme;
    cache.exp = &exp;
    cache.file = exp.setup().file;
    cache.name = exp.setup().name;
  }
  // Paused (no step since the last frame): what changed is shown at once.
  const bool paused = exp.steps() == cache.steps;
  cache.steps = exp.steps();
  const bool new_rows = rows != cache.rows || cache.figures.empty();
  if (new_rows && (paused || now - cache.figures_at >= kPlotRefresh)) {
    // The figure list can change during a run (an estimator switched on adds its figure).
    cache.figures = exp.Figures();
    cache.figures_at = now;
    cache.rows = rows;
  }
  if (ImGui::BeginTabBar("tabs")) {
    // A lesson file's text comes first (formsim gui --lesson NAME opens on it).
    if (session_->lesson().present && ImGui::BeginTabItem("Lesson", nullptr, tab("Lesson"))) {
      if (auto* lesson = Find<LessonPanel>()) lesson->Draw(fonts);
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Plots", nullptr, tab("Plots"))) {
      const auto& figures = cache.figures;
      // The user's choices are kept by figure id.
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
      // What DecoratePlot adds: a drawn plot is kept only while it is unchanged.
      std::string decoration =
          compare_->Decoration() + (state_.settings.degrees ? "/deg" : "/rad");
      for (const std::string& id : state_.plot_log_y) decoration += "|log:" + id;
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
        // A time plot's log-y toggle on a line of its own above it (the log-y command).
        if (IsTimePlot(figures[i])) {
          bool log_y = state_.plot_log_y.count(figures[i].id) > 0;
          if (ImGui::Checkbox(("log y##" + figures[i].id).c_str(), &log_y))
            RunCommand(*FindCommand("log-y"), figures[i].id + (log_y ? " on" : " off"),
                       CommandSource::kButton);
        }
        const ImVec2 p0 = ImGui::GetCursorScreenPos();
        const float w = ImGui::GetContentRegionAvail().x;
        const ImVec2 p1(p0.x + w, p0.y + h);
        ImGui::Dummy(ImVec2(w, h));
        if (!ImGui::IsItemVisible()) continue;  // scrolled away: skip the work
        ImDrawList* dl = ImGui::GetWindowDrawList();
        CachedPlot& plot = cache.plots[figures[i].id];
        const bool moved = p0.x != plot.p0.x || p0.y != plot.p0.y || p1.x != plot.p1.x || p1.y != plot.p1.y;
        if (!plot.valid || moved || plot.rows != cache.rows || plot.at < cache.figures_at ||
            plot.decoration != decoration) {
          // Resolved and drawn (without the cursor, which moves every frame), and kept.
          plot.data = ResolveFigure(figures[i], exp.recorder());
          compare_->DecoratePlot(figures[i], plot.data);  // pinned runs, Monte Carlo bands
          ShowPlotInUnits(plot.data, state_.settings.degrees);  // angles in the window's unit
          plot.data.log_y = state_.plot_log_y.count(figures[i].id) > 0;
          plot.decoration = decoration;
          const DrawMark mark = Mark(dl);
          plot.layout = DrawPlot(canvas, p0, p1, plot.data, style);
          plot.geometry = Capture(dl, mark);
          plot.p0 = p0, plot.p1 = p1, plot.rows = cache.rows, plot.at = now, plot.valid = true;
        } else {
          Replay(dl, plot.geometry);
        }
        const PlotData& data = plot.data;
        const PlotLayout& L = plot.layout;
        // The time cursor, as DrawPlot draws it.
        const double cursor = data.x_is_time ? CursorTime() : std::nan("");
        if (std::isfinite(cursor) && cursor >= L.x0 && cursor <= L.x1 && L.x1 > L.x0) {
          const float x = static_cast<float>(L.area_min.x + (cursor - L.x0) *
                                                                  (L.area_max.x - L.area_min.x) /
                                                                  (L.x1 - L.x0));
          canvas.PushClip(L.area_min, L.area_max);
          canvas.Line(ImVec2(x, L.area_min.y), ImVec2(x, L.area_max.y), {style.theme->cursor, 1.0f});
          canvas.PopClip();
        }
        // Hovering shows each series' value under the mouse.
        if (ImGui::IsItemHovered() && !data.equal_aspect) {
          const ImVec2 m = ImGui::GetIO().MousePos;
          if (m.x >= L.area_min.x && m.x <= L.area_max.x) {
            const double x =
                L.x0 + (m.x - L.area_min.x) / (L.area_max.x - L.area_min.x) * (L.x1 - L.x0);
            ImGui::BeginTooltip();
            ImGui::Text("%s = %.4g", MarkupText(data.x_label).c_str(), x);
            // At most 40 rows of at most 80 bytes each: a tooltip is one draw list of 16-bit
            // indices (a swarm's thousand series or a 100,000-character name would abort).
            int rows = 0, more = 0;
            for (const auto& s : data.series) {
              const double y = SampleSeries(s, x);
              if (std::isfinite(y) && !s.label.empty()) {
                if (rows >= 40) {
                  ++more;
                  continue;
                }
                ++rows;
                const sim::Color c = style.theme->Series(s.color, s.style_index, s.dashed).color;
                ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1), "%s: %.5g",
                                   Shorten(MarkupText(s.label), 80).c_str(), y);
              }
            }
            if (more > 0) ImGui::TextDisabled("... %d more", more);
            ImGui::EndTooltip();
          }
        }
      }
      ImGui::EndChild();
      ImGui::EndTabItem();
    }
    // The results as tables (the same metrics as summary.json), then the experiment's own;
    // computed once to know whether there are any, then only while the tab is shown.
    auto refresh_tables = [&] {
      cache.results = exp.Results();
      cache.tables = cache.results.GuiTables();
      for (auto& t : exp.Tables()) cache.tables.push_back(std::move(t));
      cache.tables_at = now;
      cache.tables_steps = exp.steps();
      cache.tables_valid = true;
    };
    if (!cache.tables_valid) refresh_tables();
    if (!cache.tables.empty() && ImGui::BeginTabItem("Tables", nullptr, tab("Tables"))) {
      if (exp.steps() != cache.tables_steps && (paused || now - cache.tables_at >= kTableRefresh))
        refresh_tables();
      compare_->DrawCompareTable(cache.results);
      const std::vector<sim::TableSpec>& tables = cache.tables;
      for (std::size_t t = 0; t < tables.size(); ++t) {
        const sim::TableSpec& spec = tables[t];
        ImGui::TextUnformatted(spec.title.c_str());
        const int cols = static_cast<int>(spec.header.size()) + (spec.row_strength.empty() ? 0 : 1);
        if (cols == 0) continue;
        ImGui::PushID(static_cast<int>(t));
        if (ImGui::BeginTable("tbl", cols,
                              ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                  ImGuiTableFlags_SizingStretchProp)) {
          // Headers in the unit shown (angles in the window's unit), never cut mid-unit; the
          // numbers of a column with the comparison table's formatter, in that unit.
          std::vector<std::string> headers;
          std::vector<double> scale;
          for (const auto& h : spec.header) {
            headers.push_back(ShownLabel(h, state_.settings.degrees));
            scale.push_back(ShownUnit(LabelUnit(h), state_.settings.degrees).scale);
            ImGui::TableSetupColumn(headers.back().c_str());
          }
          if (!spec.row_strength.empty()) {
            ImGui::TableSetupColumn("strength");
            headers.push_back("strength");
          }
          TableHeaders(headers);
          // The results' own tables come first (GuiTables keeps their order).
          const auto& result_tables = cache.results.tables();
          const sim::Metrics::Table* metrics = t < result_tables.size() ? &result_tables[t] : nullptr;
          // Only the rows in view are laid out (a thousand links make thousands of rows).
          ImGuiListClipper clipper;
          clipper.Begin(static_cast<int>(spec.rows.size()));
          while (clipper.Step()) {
            for (int r = clipper.DisplayStart; r < clipper.DisplayEnd; ++r) {
              ImGui::TableNextRow();
              for (std::size_t c = 0; c < spec.header.size(); ++c) {
                ImGui::TableSetColumnIndex(static_cast<int>(c));
                if (c >= spec.rows[r].size()) continue;
                // A metric from its value (not from its rounded text), another table's number
                // from its text.
                double x = 0;
                const double* value = nullptr;
                if (metrics != nullptr && c >= 1 && static_cast<std::size_t>(r) < metrics->rows.size() &&
                    c - 1 < metrics->columns.size()) {
                  const std::string& prefix = metrics->rows[r].second;
                  const std::string& path = metrics->columns[c - 1].path;
                  value = cache.results.Find(prefix.empty() ? path : prefix + "." + path);
                }
                const std::string& cell = spec.rows[r][c];
                if (value == nullptr && sim::ParseFiniteDouble(cell, &x)) value = &x;
                ImGui::TextUnformatted(value != nullptr ? sim::FormatCell(*value * scale[c], 4).c_str()
                                                        : cell.c_str());
              }
              if (!spec.row_strength.empty()) {
                ImGui::TableSetColumnIndex(static_cast<int>(spec.header.size()));
                const double s = static_cast<std::size_t>(r) < spec.row_strength.size()
                                     ? spec.row_strength[r]
                                     : 0.0;
                ImGui::ProgressBar(
                    static_cast<float>(std::clamp(std::isfinite(s) ? s : 0.0, 0.0, 1.0)),
                    ImVec2(-1, 0));
              }
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
      compare_->DrawPinnedRuns();
      history_->Draw(fonts);
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Summary", nullptr, tab("Summary"))) {
      if (cache.summary_steps != exp.steps() &&
          (cache.summary.empty() || paused || now - cache.summary_at >= kTableRefresh)) {
        cache.summary = exp.SummaryText();
        cache.summary_at = now;
        cache.summary_steps = exp.steps();
      }
      ImGui::PushFont(fonts.mono);
      ImGui::TextUnformatted(cache.summary.c_str());
      ImGui::PopFont();
      ImGui::Separator();
      const auto& events = exp.events().list();
      ImGui::Text("%zu events", events.size());
      ImGuiListClipper clipper;
      clipper.Begin(static_cast<int>(events.size()));
      while (clipper.Step())
        for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
          const auto& e = events[static_cast<std::size_t>(i)];
          ImGui::Text("%.2f s  %s  %s: %s", e.time, e.kind.c_str(), e.robots.c_str(),
                      e.message.c_str());
        }
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
}

}  // namespace formsim::app
