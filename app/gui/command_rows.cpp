/// \file The rows of the window's command table (app/gui/command_table.hpp), assembled from the
/// panels' rows. Each panel registers its own rows: the panel classes (app/gui/panel.hpp) in
/// their files (ComparePanel::Rows, FormationEditorPanel::Rows, HistoryPanel::Rows,
/// LessonPanel::Rows, TimelinePanel::Rows); the rows
/// of the parts still drawn by the window class (AppUi) are the functions below, one per part.
/// A command's name is written once, in its row.
///
/// The table's order, fixed: the parts in the order of kPanelOrder below, then grouped by menu,
/// File, Run, View, Compare, the script-only rows, the kinds' menus (Formation), Help, keeping
/// the parts' order inside each group. That is the order of the menu bar, the palette,
/// `formsim gui --list-commands` and the README's table.
#include <cerrno>
#include <cstring>
#include <fstream>
#include <algorithm>
#include <filesystem>

#include "app/gui/command_table.hpp"
#include "app/render/long_text.hpp"
#include "app/export/figure_data.hpp"
#include "app/export/figure_export.hpp"
#include "app/gui/command_row_makers.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/gui/formation_editor_panel.hpp"
#include "app/gui/history_panel.hpp"
#include "app/gui/lesson_panel.hpp"
#include "app/gui/parameters_panel.hpp"
#include "app/gui/plots_panel.hpp"
#include "app/gui/run_panel.hpp"
#include "app/gui/scenario_panel.hpp"
#include "app/gui/timeline_panel.hpp"
#include "app/gui/view_panel.hpp"
#include "app/gui/ui.hpp"
#include "sim/core/draw.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/provenance.hpp"
#include "sim/scenario/scenario_files.hpp"

namespace fs = std::filesystem;

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace formsim::app {
namespace {

using Src = CommandSource;
using namespace rows;

// ---- what the window offers now ----

// ---- when a command can run ----

// Session: the session record and its journal (app/gui/ui_session.cpp, ui_journal.cpp).
std::vector<Command> SessionRows() {
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "save-session",
       .args = {Initial(Text("PATH", "a session file to write"),
                        [](const AppUi& ui) { return std::string(ui.state().session_path); })},
       .menu = "File/Save session…",
       .help = "Write the session so far (every edit with its step); replay it with formsim replay",
       .run = [](AppUi& ui, const CommandArgs& a, Src) { return ui.CmdSaveSession(a.Text(0)); }});
  // Crash-safe sessions (app/gui/ui_journal.cpp): an unfinished session offered at start.
  row({.name = "restore-session",
       .menu = "File/Restore unfinished session",
       .help = "Replay the unfinished session of a window that was killed, and go on from it",
       .disabled =
           [](const AppUi& ui) {
             return ui.unfinished_sessions().empty() ? std::string("no unfinished session")
                                                     : std::string();
           },
       .run = [](AppUi& ui, const CommandArgs&, Src) { return ui.CmdRestoreSession(); }});
  row({.name = "discard-session",
       .menu = "File/Discard unfinished session",
       .help = "Delete the journal of the unfinished session offered at start",
       .disabled =
           [](const AppUi& ui) {
             return ui.unfinished_sessions().empty() ? std::string("no unfinished session")
                                                     : std::string();
           },
       .run = [](AppUi& ui, const CommandArgs&, Src) { return ui.CmdDiscardSession(); }});
  return t;
}

// Palette: the command palette.
std::vector<Command> PaletteRows() {
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "palette",
       .args = {Optional(Text("FILTER", "text to filter commands and tunables by"))},
       .keys = {"Ctrl+K"},
       .menu = "Help/Command palette",
       .help = "Find any command or tunable by typing part of its name",
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return ui.CmdPalette(a.Has(0) ? a.Text(0) : "");
       }});
  return t;
}

// Window: the window itself: quitting, Esc, menus, scripts, About.
std::vector<Command> WindowRows() {
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "quit",
       .keys = {"Ctrl+Q"},
       .menu = "File/Quit",
       .help = "Close the window (with --out and --session, their files are written first)",
       .run =
           [](AppUi& ui, const CommandArgs&, Src) {
             ui.state().quit_requested = true;
             return std::string();
           },
       .ends_program = true});
  row({.name = "dismiss",
       .keys = {"Esc"},
       .menu = "View/Close what is open",
       .help = "Close the palette or help, stop editing, or leave presentation (one at a time)",
       .run = [](AppUi& ui, const CommandArgs&, Src) {
         UiState& s = ui.state();
         if (s.palette)
           s.palette = false;
         else if (s.help)
           s.help = false;
         else if (Panel* open = ui.PanelToDismiss())
           return open->Dismiss();  // the formation editor stops editing
         else if (s.present)
           return ui.Find<ViewPanel>()->CmdPresent(false);
         return std::string();
       }});
  row({.name = "menu",
       .args = {Choice("NAME", {"File", "Run", "View", "Compare", "Formation", "Help"})},
       .help = "Open a menu of the menu bar (for scripted pictures and tests)",
       .run =
           [](AppUi& ui, const CommandArgs& a, Src) {
             ui.state().open_menu = a.Text(0);
             return std::string();
           },
       .script_only = true});
  row({.name = "layout-report",
       .args = {Text("PATH", "a JSON file to write")},
       .help = "Write what the layout cut off in this frame (window, UI scale, clipped text) as JSON",
       .run =
           [](AppUi& ui, const CommandArgs& a, Src) {
             // The report is written at the end of the frame; a path that cannot be written is
             // refused now, so that the script says so with its line.
             const std::string path = a.Text(0);
             std::ofstream probe(path, std::ios::app);
             if (!probe) return "layout-report: cannot write '" + Shorten(path, 200) + "': " + std::strerror(errno);
             ui.state().layout_report_path = path;
             return std::string();
           },
       .script_only = true});
  row({.name = "wait",
       .help = "Hold the script until pins, a Monte Carlo or the timeline have finished",
       .run = [](AppUi&, const CommandArgs&, Src) { return std::string(); },
       .script_only = true});
  row({.name = "about",
       .menu = "Help/About",
       .help = "formsim's version and where its papers come from",
       .run = [](AppUi& ui, const CommandArgs&, Src) {
         ui.state().about = true;
         return std::string();
       }});
  return t;
}

// The parts whose rows make the table, in this order (see the file's comment).
using RowsOf = std::vector<Command> (*)();
const RowsOf kPanelOrder[] = {
    ScenarioPanel::Rows, SessionRows, RunPanel::Rows,      ParametersPanel::Rows,               ViewPanel::Rows,
    PlotsPanel::Rows, ComparePanel::Rows, HistoryPanel::Rows,          ParametersPanel::UndoRows,     TimelinePanel::Rows,
    FormationEditorPanel::Rows, PaletteRows,                 LessonPanel::Rows,
    WindowRows,
};

// The group of a row in the table: its menu's place; script-only rows after Compare.
int GroupOf(const Command& c) {
  static const std::vector<std::string> kGroups = {"File", "Run", "View", "Compare", "",
                                                   "Formation", "Help"};
  const std::string top = c.menu.substr(0, c.menu.find('/'));
  const auto it = std::find(kGroups.begin(), kGroups.end(), top);
  // A menu of a kind not listed goes with the kinds' menus, before Help.
  return it == kGroups.end() ? 5 : static_cast<int>(it - kGroups.begin());
}

std::vector<Command> BuildTable() {
  std::vector<Command> t;
  for (RowsOf rows_of : kPanelOrder)
    for (Command& c : rows_of()) t.push_back(std::move(c));
  std::stable_sort(t.begin(), t.end(),
                   [](const Command& a, const Command& b) { return GroupOf(a) < GroupOf(b); });
  return t;
}

}  // namespace

const std::vector<Command>& Commands() {
  static const std::vector<Command> kTable = BuildTable();
  return kTable;
}

std::string AboutText() {
  return "formsim " + sim::FormsimVersion() +
         "\nA 2-D simulator for multi-robot formation control and mobile-robot navigation.\n"
         "Box2D bodies, controllers and estimators from four papers, Dear ImGui + GLFW.";
}

}  // namespace formsim::app
