#include "app/gui/plots_panel.hpp"

#include "app/gui/frame_audit.hpp"

#include "app/gui/flow_layout.hpp"

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
#include "app/gui/ui.hpp"
#include "app/render/imgui_canvas.hpp"
#include "app/render/label_markup.hpp"
#include "app/render/long_text.hpp"
#include "app/render/plot_units.hpp"
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
};

PlotsPanel::PlotsPanel(const PanelContext& ctx) : ctx_(ctx), cache_(std::make_unique<Cache>()) {}
PlotsPanel::~PlotsPanel() = default;

void PlotsPanel::Draw(const Fonts& fonts) {
  const sim::Experiment& exp = ctx_.session().exp();
  Cache& cache = *cache_;
  const Clock::time_point now = Clock::now();
  const std::size_t rows = exp.recorder().rows_sampled();
  // A new run (or the same one reset: fewer rows or steps than before) drops everything.
  if (&exp != cache.exp || rows < cache.rows || exp.steps() < cache.steps ||
      exp.setup().file != cache.file || exp.setup().name != cache.name ||
      ctx_.state->theme != cache.theme) {
    cache = Cache{};
    cache.theme = ctx_.state->theme;
    cache.exp = &exp;
    cache.file = exp.setup().file;
    cache.name = exp.setup().name;
  }
  // Paused (no step since the last frame): what changed is shown at once.
  const bool paused = exp.steps() == cache.steps;
  cache.steps = exp.steps();
  const bool new_rows = rows != cache.rows || cache.figures.empty();
  if (new_rows &&
      (paused || ctx_.state->plots_every_frame || now - cache.figures_at >= kPlotRefresh)) {
    // The figure list can change during a run (an estimator switched on adds its figure).
    cache.figures = exp.Figures();
    cache.figures_at = now;
    cache.rows = rows;
  }
  ComparePanel* compare = ctx_.Find<ComparePanel>();
  const auto& figures = cache.figures;
  // The user's choices are kept by figure id.
  auto is_open = [&](const sim::FigureSpec& f) {
    const auto it = closed_.find(f.id);
    return it == closed_.end() || !it->second;
  };
  // Toggles for each figure, then the open ones stacked (scrolling when they do not fit).
  for (std::size_t i = 0; i < figures.size(); ++i) {
    bool open = is_open(figures[i]);
    const std::string id = figures[i].id + "##toggle";
    if (i > 0) SameLineIfFits(CheckboxWidth(id.c_str()));
    if (ImGui::Checkbox(id.c_str(), &open)) closed_[figures[i].id] = !open;
  }
  ImGui::BeginChild("plot_list", ImVec2(0, 0), false);
  int open_count = 0;
  for (const auto& f : figures) open_count += is_open(f);
  const float avail_h = ImGui::GetContentRegionAvail().y;
  // Plots reflow into as many columns as fit at kMinPlotWidth each; up to three rows share the
  // height, more scroll.
  const float gap = ImGui::GetStyle().ItemSpacing.x;
  const float full_w = ImGui::GetContentRegionAvail().x;
  const int cols = std::max(1, static_cast<int>((full_w + gap) / (kMinPlotWidth + gap)));
  const float w = std::max(1.0f, std::floor((full_w - static_cast<float>(cols - 1) * gap) / cols));
  const int plot_rows = (open_count + cols - 1) / cols;
  // Whole pixels, so that each plot's background is a clear (ImGuiCanvas::FillBackground).
  const float h =
      std::max(220.0f, plot_rows > 0 ? std::floor(avail_h / std::min(plot_rows, 3)) - 6 : 0);
  // What DecoratePlot adds: a drawn plot is kept only while it is unchanged.
  std::string decoration =
      compare->Decoration() + (ctx_.state->settings.degrees ? "/deg" : "/rad");
  for (const std::string& id : log_y_) decoration += "|log:" + id;
  PlotStyle style;
  style.title_font = FontRole::kLabel;
  style.label_font = FontRole::kUi;
  style.tick_font = FontRole::kSmall;
  style.line_width = 1.6f;
  style.padding = 6;
  style.theme = &GetTheme(ctx_.state->theme);
  ImGuiCanvas canvas(ImGui::GetWindowDrawList(), fonts);
  canvas.SetWholePixelLines(true);  // the window's level of detail (exported figures keep theirs)
  auto draw_cell = [&](std::size_t i) {
    // A time plot's log-y toggle on a line of its own above it (the log-y command).
    if (IsTimePlot(figures[i])) {
      bool log_y = LogY(figures[i].id);
      if (ImGui::Checkbox(("log y##" + figures[i].id).c_str(), &log_y))
        ctx_.run("log-y " + figures[i].id + (log_y ? " on" : " off"));
    }
    CachedPlot& plot = cache.plots[figures[i].id];
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    const ImVec2 p1(p0.x + w, p0.y + h + plot.extra_h);
    ImGui::Dummy(ImVec2(w, h + plot.extra_h));
    if (!ImGui::IsItemVisible()) return;  // scrolled away: skip the work
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const bool moved = p0.x != plot.p0.x || p0.y != plot.p0.y || p1.x != plot.p1.x || p1.y != plot.p1.y;
    if (!plot.valid || moved || plot.rows != cache.rows || plot.at < cache.figures_at ||
        plot.decoration != decoration) {
      // Resolved and drawn (without the cursor, which moves every frame), and kept.
      plot.data = ResolveFigure(figures[i], exp.recorder());
      compare->DecoratePlot(figures[i], plot.data);  // pinned runs, Monte Carlo bands
      ShowPlotInUnits(plot.data, ctx_.state->settings.degrees);  // angles in the window's unit
      plot.data.log_y = LogY(figures[i].id);
      plot.decoration = decoration;
      const DrawMark mark = Mark(dl);
      plot.layout = DrawPlot(canvas, p0, p1, plot.data, style);
      plot.geometry = Capture(dl, mark);
      // A data area under kSmallestPlotPx (in pixels: logical units times the UI scale) grows
      // its cell from the next frame on.
      const float want = kSmallestPlotPx / std::max(1.0f, ImGui::GetIO().DisplayFramebufferScale.x) + 1;
      const float area_h = plot.layout.area_max.y - plot.layout.area_min.y;
      if (area_h < want) plot.extra_h = std::min(plot.extra_h + want - area_h, 2000.0f);
      plot.p0 = p0, plot.p1 = p1, plot.rows = cache.rows, plot.at = now, plot.valid = true;
    } else {
      Replay(dl, plot.geometry);
    }
    const PlotData& data = plot.data;
    const PlotLayout& L = plot.layout;
    ctx_.state->frame_plots.push_back(
        {figures[i].id, ImVec4(L.area_min.x, L.area_min.y, L.area_max.x, L.area_max.y)});
    // The time cursor, as DrawPlot draws it.
    const double cursor = data.x_is_time ? ctx_.shown().time() : std::nan("");
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
  };
  int cell = 0;
  for (std::size_t i = 0; i < figures.size(); ++i) {
    if (!is_open(figures[i])) continue;
    if (cell++ % cols != 0) ImGui::SameLine();
    ImGui::BeginGroup();
    draw_cell(i);
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
