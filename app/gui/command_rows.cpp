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
#include <algorithm>
#include <filesystem>

#include "app/gui/command_table.hpp"
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

std::vector<std::string> OverlayNames(const AppUi&) {
  std::vector<std::string> out = {"all", "none", "default"};
  for (const sim::OverlayInfo& o : sim::Overlays()) out.push_back(o.name);
  return out;
}

std::vector<std::string> ThemeList() {
  std::vector<std::string> out;
  for (ThemeId id : {ThemeId::kLight, ThemeId::kDark, ThemeId::kPrint, ThemeId::kHighContrast})
    out.push_back(GetTheme(id).name);
  return out;
}

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

// View: the View section and the world view: camera, theme, overlays, legend, help, screenshots.
std::vector<Command> ViewRows() {
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "screenshot",
       .args = {Optional(Text("PATH", "a PNG file to write"))},
       .keys = {"s"},
       .menu = "File/Screenshot",
       .help = "Write the window as a PNG (to PATH, else a numbered name)",
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return ui.CmdScreenshot(a.Has(0) ? a.Text(0) : "");
       }});
  row({.name = "present",
       .args = {OnOff()},
       .keys = {"p"},
       .key_args = "toggle",
       .menu = "View/Presentation mode",
       .help = "The world view fills the window, for a lecture room (Esc leaves)",
       .checked = [](const AppUi& ui) { return ui.state().present; },
       .run = [](AppUi& ui, const CommandArgs& a, Src) { return ui.CmdPresent(a.On(0)); }});
  row({.name = "frame-formation",
       .args = {OnOff()},
       .key_args = "toggle",
       .menu = "View/Frame the formation",
       .help = "The camera frames the robots and their recent trails and follows them (always on "
               "in presentation mode; zooming by hand pauses it until fit)",
       .checked = [](const AppUi& ui) { return ui.state().frame_formation; },
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         ui.state().frame_formation = a.On(0);
         ui.state().camera.Fit();
         return std::string();
       }});
  row({.name = "theme",
       .args = {Initial(
           Choice("NAME", ThemeList()),
           [](const AppUi& ui) { return std::string(GetTheme(ui.state().theme).name); })},
       .menu = "View/Theme",
       .help = "Colours of the panels, the world view and the plots",
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         ui.state().theme = ParseTheme(a.Text(0));
         if (ImGui::GetCurrentContext() != nullptr) ApplyImGuiTheme(GetTheme(ui.state().theme));
         return std::string();
       }});
  row({.name = "ui-scale",
       .args = {Initial(
           Offer(Real("SCALE", kMinUiScale, kMaxUiScale),
                 [](const AppUi&) {
                   return std::vector<std::string>{"1", "1.25", "1.5", "2", "2.5", "3"};
                 }),
           [](const AppUi& ui) { return sim::FormatDouble(ui.state().settings.ui_scale); })},
       .menu = "View/UI scale",
       .help = "Fonts and line widths, kept between runs",
       .run = [](AppUi& ui, const CommandArgs& a, Src) { return ui.CmdUiScale(a.Real(0)); }});
  row({.name = "angle-unit",
       .args = {Initial(Choice("UNIT", {"deg", "rad"}),
                        [](const AppUi& ui) {
                          return std::string(ui.state().settings.degrees ? "deg" : "rad");
                        })},
       .menu = "View/Angle unit",
       .help = "Show angles in degrees or radians (stored values stay radians)",
       .run = [](AppUi& ui, const CommandArgs& a, Src) { return ui.CmdAngleUnit(a.Text(0)); }});
  row({.name = "overlay",
       .args = {Offer(Text("LIST", "overlay names, comma-separated (all, none, default, -NAME)"),
                      OverlayNames)},
       .menu = "View/Overlays",
       .help = "What the law sees, drawn over the scene: applied to the overlays shown now",
       .run = [](AppUi& ui, const CommandArgs& a, Src) { return ui.CmdOverlay(a.Text(0)); }});
  row({.name = "legend",
       .args = {OnOff()},
       .keys = {"l"},
       .key_args = "toggle",
       .menu = "View/Legend",
       .help = "A legend of every mark in the world view",
       .checked = [](const AppUi& ui) { return ui.state().legend; },
       .run = [](AppUi& ui, const CommandArgs& a, Src) { return ui.CmdLegend(a.On(0)); }});
  row({.name = "follow",
       .args = {Initial(
           Offer(Text("ROBOT", "a robot's name, or nobody", ArgType::kChoice), RobotNames),
           [](const AppUi& ui) {
             const auto names = RobotNames(ui);
             const int f = ui.state().follow;
             return f >= 0 && f + 1 < static_cast<int>(names.size()) ? names[f + 1] : names[0];
           })},
       .menu = "View/Follow",
       .help = "Keep a robot in the middle of the world view (nobody: fit)",
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         const auto names = RobotNames(ui);
         for (std::size_t i = 0; i < names.size(); ++i)
           if (names[i] == a.Text(0)) ui.state().follow = static_cast<int>(i) - 1;
         ui.state().auto_fit = ui.state().follow < 0;
         ui.state().fit_now = ui.state().follow < 0;
         return std::string();
       }});
  row({.name = "fit",
       .keys = {"f"},
       .menu = "View/Fit everything",
       .help = "Fit everything in view (and stop following)",
       .run = [](AppUi& ui, const CommandArgs&, Src) {
         ui.state().fit_now = true;
         ui.state().camera.Fit();
         ui.state().follow = -1;
         return std::string();
       }});
  row({.name = "tab",
       .args = {Choice("NAME", {"plots", "tables", "history", "summary", "lesson"})},
       .menu = "View/Show tab",
       .help = "Bring a tab of the right-hand window to the front",
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         ui.state().select_tab = a.Text(0);
         return std::string();
       }});
  row({.name = "help",
       .args = {OnOff()},
       .keys = {"F1", "?"},
       .key_args = "toggle",
       .menu = "Help/Keys and mouse",
       .help = "The help overlay: every key and mouse gesture",
       .checked = [](const AppUi& ui) { return ui.state().help; },
       .run = [](AppUi& ui, const CommandArgs& a, Src) { return ui.CmdHelp(a.On(0)); }});
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
           return ui.CmdPresent(false);
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
    ScenarioPanel::Rows, SessionRows, RunPanel::Rows,      ParametersPanel::Rows,               ViewRows,
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
