#include "app/gui/plots_panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "app/export/figure_data.hpp"
#include "app/export/figure_export.hpp"
#include "app/gui/command_row_makers.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/gui/flow_layout.hpp"
#include "app/gui/frame_audit.hpp"
#include "app/gui/ui.hpp"
#include "app/render/imgui_canvas.hpp"
#include "app/render/label_markup.hpp"
#include "app/render/long_text.hpp"
#include "app/render/plot_units.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/session/session.hpp"

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace formsim::app {

// Named, not anonymous: CachedPlot (held by PlotsPanel::Cache) has one as a field.
// The geometry one DrawPlot call appended to a draw list: its vertices, its indices (relative
// to those vertices) and, per draw command, the clip rectangle, texture and index range.
struct DrawnGeometry {
  struct Cmd {
    ImVec4 clip;
    ImTextureID texture;
    int idx_begin = 0, idx_count = 0;
    ImDrawCallback callback = nullptr;  ///< a draw callback (the background's clear), no indices
    void* callback_data = nullptr;
  };
  std::vector<ImDrawVert> vtx;
  std::vector<int> idx;
  std::vector<Cmd> cmds;
};

namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPlotRefresh = std::chrono::milliseconds(100);

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
    // A callback in the command open at the mark was added after it (AddCallback always opens
    // a new command behind its own).
    if (cmd.UserCallback != nullptr) {
      g.cmds.push_back({cmd.ClipRect, cmd.TextureId, 0, 0, cmd.UserCallback, cmd.UserCallbackData});
      continue;
    }
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
// shares; a callback again under its clip rectangle).
void Replay(ImDrawList* dl, const DrawnGeometry& g) {
  for (const DrawnGeometry::Cmd& c : g.cmds) {
    if (c.callback != nullptr) {
      dl->PushClipRect(ImVec2(c.clip.x, c.clip.y), ImVec2(c.clip.z, c.clip.w), false);
      dl->AddCallback(c.callback, c.callback_data);
      dl->PopClipRect();
      continue;
    }
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
  /// Height added to the cell so that its data area keeps kSmallestPlotPx (a legend below the
  /// axes, a large UI scale).
  float extra_h = 0;
};

struct PlotsPanel::Cache {
  // Which run and how far: a change of run (reset, load) or new rows call for a refresh.
  const sim::Experiment* exp = nullptr;
  std::string file, name;
  ThemeId theme = ThemeId::kLight;
  std::size_t rows = 0;
  long steps = -1;
  std::vector<sim::FigureSpec> figures;
  Clock::time_point figures_at;
  std::map<std::string, CachedPlot> plots;

  /// Follows run `exp` drawn in `theme_now`: a new run (or the same one reset: fewer rows or
  /// steps than before) drops everything; new rows refresh the figure list when paused, when
  /// `every_frame`, else at most every kPlotRefresh.
  void Follow(const sim::Experiment& exp_now, ThemeId theme_now, bool every_frame,
              Clock::time_point now) {
    const std::size_t rows_now = exp_now.recorder().rows_sampled();
    if (&exp_now != exp || rows_now < rows || exp_now.steps() < steps ||
        exp_now.setup().file != file || exp_now.setup().name != name || theme_now != theme) {
      *this = Cache{};
      theme = theme_now;
      exp = &exp_now;
      file = exp_now.setup().file;
      name = exp_now.setup().name;
    }
    // Paused (no step since the last frame): what changed is shown at once.
    const bool paused = exp_now.steps() == steps;
    steps = exp_now.steps();
    const bool new_rows = rows_now != rows || figures.empty();
    if (new_rows && (paused || every_frame || now - figures_at >= kPlotRefresh)) {
      // The figure list can change during a run (an estimator switched on adds its figure).
      figures = exp_now.Figures();
      figures_at = now;
      rows = rows_now;
    }
  }
};

namespace {

// The user's choices are kept by figure id.
bool PlotIsOpen(const std::map<std::string, bool>& closed, const sim::FigureSpec& f) {
  const auto it = closed.find(f.id);
  return it == closed.end() || !it->second;
}

// A toggle for each figure, wrapping.
void DrawPlotToggles(const std::vector<sim::FigureSpec>& figures,
                     std::map<std::string, bool>& closed) {
  for (std::size_t i = 0; i < figures.size(); ++i) {
    bool open = PlotIsOpen(closed, figures[i]);
    const std::string id = figures[i].id + "##toggle";
    if (i > 0) SameLineIfFits(CheckboxWidth(id.c_str()));
    if (ImGui::Checkbox(id.c_str(), &open)) closed[figures[i].id] = !open;
  }
}

// The plots' cells: as many columns as fit at kMinPlotWidth each; up to three rows share the
// height, more scroll.
struct PlotGridCells {
  int cols = 1;
  float w = 1, h = 0;
};

PlotGridCells PlotGridFor(int open_count) {
  PlotGridCells g;
  const float avail_h = ImGui::GetContentRegionAvail().y;
  const float gap = ImGui::GetStyle().ItemSpacing.x;
  const float full_w = ImGui::GetContentRegionAvail().x;
  g.cols = std::max(1, static_cast<int>((full_w + gap) / (PlotsPanel::kMinPlotWidth + gap)));
  g.w = std::max(1.0f, std::floor((full_w - static_cast<float>(g.cols - 1) * gap) / g.cols));
  const int plot_rows = (open_count + g.cols - 1) / g.cols;
  // Whole pixels, so that each plot's background is a clear (ImGuiCanvas::FillBackground).
  g.h = std::max(220.0f, plot_rows > 0 ? std::floor(avail_h / std::min(plot_rows, 3)) - 6 : 0);
  return g;
}

PlotStyle PlotsPanelStyle(const Theme& theme) {
  PlotStyle style;
  style.title_font = FontRole::kLabel;
  style.label_font = FontRole::kUi;
  style.tick_font = FontRole::kSmall;
  style.line_width = 1.6f;
  style.padding = 6;
  style.theme = &theme;
  return style;
}

// What every plot cell of one frame shares.
struct PlotsPanelFrame {
  const sim::Experiment& exp;
  ComparePanel& compare;
  ImGuiCanvas& canvas;
  const PlotStyle& style;
  const std::string& decoration;  ///< what DecoratePlot adds, the angle unit, the log axes
  bool degrees;
  PlotGridCells grid;
  std::size_t rows;  ///< the recorder's rows the figure list was taken at
  Clock::time_point figures_at, now;
};

// Figure `fig` in its cell p0..p1: resolved and drawn (without the cursor, which moves every
// frame) and kept when anything changed; else the drawing kept is appended again.
void DrawOrReplayPlot(CachedPlot& plot, const sim::FigureSpec& fig, bool log_y,
                      const PlotsPanelFrame& f, ImVec2 p0, ImVec2 p1) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const bool moved =
      p0.x != plot.p0.x || p0.y != plot.p0.y || p1.x != plot.p1.x || p1.y != plot.p1.y;
  const bool stale = !plot.valid || moved || plot.rows != f.rows || plot.at < f.figures_at ||
                     plot.decoration != f.decoration;
  if (!stale) {
    Replay(dl, plot.geometry);
    return;
  }
  plot.data = ResolveFigure(fig, f.exp.recorder());
  f.compare.DecoratePlot(fig, plot.data);  // pinned runs, Monte Carlo bands
  ShowPlotInUnits(plot.data, f.degrees);   // angles in the window's unit
  plot.data.log_y = log_y;
  plot.decoration = f.decoration;
  const DrawMark mark = Mark(dl);
  plot.layout = DrawPlot(f.canvas, p0, p1, plot.data, f.style);
  plot.geometry = Capture(dl, mark);
  // A data area under kSmallestPlotPx (in pixels: logical units times the UI scale) grows
  // its cell from the next frame on.
  const float want = kSmallestPlotPx / std::max(1.0f, ImGui::GetIO().DisplayFramebufferScale.x) + 1;
  const float area_h = plot.layout.area_max.y - plot.layout.area_min.y;
  if (area_h < want) plot.extra_h = std::min(plot.extra_h + want - area_h, 2000.0f);
  plot.p0 = p0, plot.p1 = p1, plot.rows = f.rows, plot.at = f.now, plot.valid = true;
}

// The time cursor at `cursor` (nan: none), as DrawPlot draws it.
void DrawPlotCursor(ImGuiCanvas& canvas, const PlotLayout& L, double cursor, const Theme& theme) {
  if (std::isfinite(cursor) && cursor >= L.x0 && cursor <= L.x1 && L.x1 > L.x0) {
    const float x = static_cast<float>(
        L.area_min.x + (cursor - L.x0) * (L.area_max.x - L.area_min.x) / (L.x1 - L.x0));
    canvas.PushClip(L.area_min, L.area_max);
    canvas.Line(ImVec2(x, L.area_min.y), ImVec2(x, L.area_max.y), {theme.cursor, 1.0f});
    canvas.PopClip();
  }
}

// Hovering the plot just drawn shows each series' value under the mouse.
void PlotHoverTooltip(const PlotData& data, const PlotLayout& L, const Theme& theme) {
  if (!ImGui::IsItemHovered() || data.equal_aspect) return;
  const ImVec2 m = ImGui::GetIO().MousePos;
  if (m.x < L.area_min.x || m.x > L.area_max.x) return;
  const double x = L.x0 + (m.x - L.area_min.x) / (L.area_max.x - L.area_min.x) * (L.x1 - L.x0);
  ImGui::BeginTooltip();
  ImGui::Text("%s", sim::Sprintf("%s = %.4g", MarkupText(data.x_label).c_str(), x).c_str());
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
      const sim::Color c = theme.Series(s.color, s.style_index, s.dashed).color;
      ImGui::TextColored(
          ImVec4(c.r, c.g, c.b, 1), "%s",
          sim::Sprintf("%s: %.5g", Shorten(MarkupText(s.label), 80).c_str(), y).c_str());
    }
  }
  if (more > 0) ImGui::TextDisabled("%s", sim::Sprintf("... %d more", more).c_str());
  ImGui::EndTooltip();
}

// One figure's cell: a time plot's log-y toggle on a line of its own above it (the log-y
// command), the plot, its time cursor and its tooltip. Nothing is drawn when scrolled away.
void DrawPlotCell(const PanelContext& ctx, const PlotsPanel& panel, const sim::FigureSpec& fig,
                  CachedPlot& plot, const PlotsPanelFrame& f) {
  if (IsTimePlot(fig)) {
    bool log_y = panel.LogY(fig.id);
    if (ImGui::Checkbox(("log y##" + fig.id).c_str(), &log_y))
      ctx.run("log-y " + fig.id + (log_y ? " on" : " off"));
  }
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const ImVec2 p1(p0.x + f.grid.w, p0.y + f.grid.h + plot.extra_h);
  ImGui::Dummy(ImVec2(f.grid.w, f.grid.h + plot.extra_h));
  if (!ImGui::IsItemVisible()) return;  // scrolled away: skip the work
  DrawOrReplayPlot(plot, fig, panel.LogY(fig.id), f, p0, p1);
  const PlotLayout& L = plot.layout;
  ctx.state->frame_plots.push_back(
      {fig.id, ImVec4(L.area_min.x, L.area_min.y, L.area_max.x, L.area_max.y)});
  const double cursor = plot.data.x_is_time ? ctx.shown().time() : std::nan("");
  DrawPlotCursor(f.canvas, L, cursor, *f.style.theme);
  PlotHoverTooltip(plot.data, L, *f.style.theme);
}

}  // namespace

PlotsPanel::PlotsPanel(const PanelContext& ctx) : ctx_(ctx), cache_(std::make_unique<Cache>()) {}
PlotsPanel::~PlotsPanel() = default;

void PlotsPanel::Draw(const Fonts& fonts) {
  const sim::Experiment& exp = ctx_.session().exp();
  Cache& cache = *cache_;
  const Clock::time_point now = Clock::now();
  cache.Follow(exp, ctx_.state->theme, ctx_.state->plots_every_frame, now);
  const auto& figures = cache.figures;
  // Toggles for each figure, then the open ones stacked (scrolling when they do not fit).
  DrawPlotToggles(figures, closed_);
  ImGui::BeginChild("plot_list", ImVec2(0, 0), false);
  int open_count = 0;
  for (const auto& f : figures) open_count += PlotIsOpen(closed_, f);
  const PlotGridCells grid = PlotGridFor(open_count);
  // What DecoratePlot adds: a drawn plot is kept only while it is unchanged.
  ComparePanel* compare = ctx_.Find<ComparePanel>();
  std::string decoration = compare->Decoration() + (ctx_.state->settings.degrees ? "/deg" : "/rad");
  for (const std::string& id : log_y_) decoration += "|log:" + id;
  const PlotStyle style = PlotsPanelStyle(GetTheme(ctx_.state->theme));
  ImGuiCanvas canvas(ImGui::GetWindowDrawList(), fonts);
  canvas.SetWholePixelLines(true);  // the window's level of detail (exported figures keep theirs)
  const PlotsPanelFrame frame{
      exp,  *compare,   canvas,           style, decoration, ctx_.state->settings.degrees,
      grid, cache.rows, cache.figures_at, now};
  int cell = 0;
  for (const sim::FigureSpec& fig : figures) {
    if (!PlotIsOpen(closed_, fig)) continue;
    if (cell++ % grid.cols != 0) ImGui::SameLine();
    ImGui::BeginGroup();
    DrawPlotCell(ctx_, *this, fig, cache.plots[fig.id], frame);
    ImGui::EndGroup();
  }
  ImGui::EndChild();
}

std::string PlotsPanel::CmdLogY(const std::string& id, bool on) {
  if (on)
    log_y_.insert(id);
  else
    log_y_.erase(id);
  return "";
}

std::string PlotsPanel::CmdExportFigures(const std::string& dir) {
  try {
    sim::PrepareOutputDir(dir);
    const sim::Experiment& exp = ctx_.session().exp();
    const Theme& theme = GetTheme(ctx_.state->theme);
    FigureSize size;
    int written = 0;
    for (const sim::FigureSpec& fig : exp.Figures()) {
      const PlotData data = ResolveFigure(fig, exp.recorder());
      if (!data.error.empty()) throw std::runtime_error("figure '" + fig.id + "': " + data.error);
      const VectorFigure recorded =
          RecordPlot(data, size.LayoutWidth(), size.LayoutHeight(), theme);
      for (FigureFormat f : kGuiFigureFormats) {
        const std::string path = dir + "/" + fig.id + "." + FormatExtension(f);
        WriteVectorFigure(recorded, f, size, data.title, path);
        ctx_.NoteFileWritten(path, FormatMime(f));
        ++written;
      }
    }
    ctx_.SetStatus("exported " + std::to_string(written) + " figure files into " + dir);
  } catch (const std::exception& e) {
    const std::string why = std::string("export failed: ") + e.what();
    ctx_.SetStatus(why, true);
    return why;
  }
  return "";
}

std::vector<Command> PlotsPanel::Rows() {
  using namespace rows;
  using Src = CommandSource;
  auto panel = [](AppUi& ui) { return ui.Find<PlotsPanel>(); };
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "export-figures",
       .args = {Initial(Text("DIR", "a folder to write into"),
                        [](const AppUi& ui) {
                          // A folder for figures beside the scenario's name.
                          return std::filesystem::path(ui.session().file()).stem().string() +
                                 "_figures";
                        })},
       .menu = "File/Export figures…",
       .help = "Write every figure of the current run as SVG and PDF into DIR",
       .run = [panel](AppUi& ui, const CommandArgs& a,
                      Src) { return panel(ui)->CmdExportFigures(a.Text(0)); }});
  row({.name = "log-y",
       .args = {Offer(Text("PLOT", "a time plot's figure id", ArgType::kChoice),
                      [](const AppUi& ui) {
                        // Plots against time (not the trajectories' equal-aspect plane, not
                        // bar charts).
                        std::vector<std::string> out;
                        for (const sim::FigureSpec& f : ui.session().exp().Figures())
                          if (IsTimePlot(f)) out.push_back(f.id);
                        return out;
                      }),
                Choice("on|off", {"on", "off"})},
       .menu = "View/Log y axis of a plot…",
       .help = "Draw a time plot's y axis in decades (values <= 0 left out, with a note)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) {
         return panel(ui)->CmdLogY(a.Text(0), a.Text(1) == "on");
       }});
  return t;
}

void PlotsPanel::Clear() {
  closed_.clear();
  log_y_.clear();
}

}  // namespace formsim::app
