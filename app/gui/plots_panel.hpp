#pragma once
/// \file The Plots panel: the live plots of the experiment's figures in the Plots tab, drawn
/// with our plot widget and a time cursor (the timeline's time when it is on), each with its
/// show/hide toggle and, for a time plot, a log-y toggle; the pinned runs and the Monte Carlo
/// bands come from the Compare panel. It owns which plots are hidden and which have a log axis,
/// and the plots as last drawn, and registers export-figures and log-y.
///
/// A thousand robots record tens of thousands of columns, so nothing here is rebuilt every
/// frame: the figures are resolved against the recorder and drawn at most ten times a second
/// (or when the data or the plot's place change), and the frames in between append the
/// geometry the last drawing produced again (only the time cursor is new).

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"

namespace formsim::app {

class PlotsPanel : public Panel {
 public:
  explicit PlotsPanel(const PanelContext& ctx);
  ~PlotsPanel() override;
  /// export-figures (File menu), log-y (View menu).
  static std::vector<Command> Rows();

  /// The narrowest a plot is drawn, in font units: its ticks and legend stay readable.
  static constexpr float kMinPlotWidth = 320.0f;

  const char* Name() const override { return "Plots"; }
  /// The Plots tab: the toggles (wrapping), then the open plots in as many columns as fit at
  /// kMinPlotWidth, scrolling when they do not fit.
  void Draw(const Fonts& fonts) override;

  /// Writes every figure of the current run as SVG and PDF into `dir`.
  std::string CmdExportFigures(const std::string& dir);
  /// Draws time plot `id`'s y axis in decades (on) or linearly (off).
  std::string CmdLogY(const std::string& id, bool on);
  /// Time plot `id` has a log y axis.
  bool LogY(const std::string& id) const { return log_y_.count(id) > 0; }
  /// Another scenario was loaded: every plot is shown again, with linear axes.
  void Clear();

 private:
  struct Cache;
  const PanelContext& ctx_;
  std::unique_ptr<Cache> cache_;       ///< the figures and each plot as last drawn
  std::map<std::string, bool> closed_;  ///< figure id -> hidden by the user
  std::set<std::string> log_y_;         ///< figure ids drawn with a log y axis
};

}  // namespace formsim::app
