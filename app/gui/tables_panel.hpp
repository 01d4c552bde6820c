#pragma once
/// \file The Tables panel: the results as tables (the same metrics as summary.json, in the
/// window's angle unit, with firing-strength bars where a table has them) under the Compare
/// panel's comparison table, in the Tables tab; and the summary text with the run's events, in
/// the Summary tab. Both are computed at most four times a second, and only while their tab is
/// shown (a thousand links make thousands of rows, laid out only where they are in view).

#include <memory>
#include <string>

#include "app/gui/panel_context.hpp"

namespace formsim::app {

class TablesPanel : public Panel {
 public:
  explicit TablesPanel(const PanelContext& ctx);
  ~TablesPanel() override;

  const char* Name() const override { return "Tables"; }
  /// The Tables tab's content: the comparison table, then every table of the results.
  void Draw(const Fonts& fonts) override;
  /// The run has tables to show.
  bool HasTables();
  /// The Summary tab's content: the summary text, then the events.
  void DrawSummary(const Fonts& fonts);
  /// What the Tables and Summary tabs show for a run that has not started (just reset, or
  /// loaded paused): "No data yet ... press Play", never a table of zeros.
  static void DrawNoData();

 private:
  struct Cache;
  /// The cache for the live run now (dropped when the run changes or is reset).
  Cache& Fresh();
  const PanelContext& ctx_;
  std::unique_ptr<Cache> cache_;
};

}  // namespace formsim::app
