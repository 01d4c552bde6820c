#pragma once
/// \file The formsim user interface, drawn with ImGui the same way in the GLFW window and in
/// headless `--ui` frames: panels Scenario, Run, Parameters (generated from the scenario's
/// ParamTable), View, Plots, Tables and Summary around the world view. Knows nothing of GLFW or
/// GL. Every user action is a command (Cmd*) called alike by buttons, keys and `--script`.

#include <imgui.h>

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "app/gui/command_table.hpp"
#include "app/gui/panel_context.hpp"
#include "app/gui/tuning_state.hpp"
#include "app/gui/ui_settings.hpp"
#include "app/render/camera.hpp"
#include "app/render/fonts.hpp"
#include "app/render/theme.hpp"
#include "app/render/view.hpp"
#include "app/render/world_view.hpp"
#include "sim/session/session.hpp"
#include "sim/session/session_journal.hpp"
#include "sim/session/session_record.hpp"

namespace formsim::app {

class ComparePanel;
class HistoryPanel;
class ParametersPanel;
class PlotsPanel;
class RunPanel;
class ScenarioPanel;
class TablesPanel;
class ViewPanel;
class TimelinePanel;

/// State of the interface that is not simulation state.
struct UiState {
  bool playing = true;
  View view;
  bool auto_fit = true;    ///< keep everything in view until the user pans or zooms
  bool whole_run = false;  ///< auto-fit shows everything since the start (else: tracks)
  bool fit_now = true;
  int follow = -1;  ///< robot index to follow, -1 none
  bool grid = true;
  bool coordinates = true;
  ThemeId theme = ThemeId::kLight;  ///< colours of the panels, the world view and the plots
  bool screenshot_requested = false;
  std::string screenshot_path;  ///< where the requested screenshot goes ("" = numbered name)
  std::string status;           ///< last message for the status line
  bool status_is_error = false;
  double status_time = 0;  ///< ImGui's clock when the status was set
  char session_path[512] = "";
  std::string gesture_key;  ///< the slider held since its last edit (its edits make one undo step)
  std::string select_tab;   ///< a tab of the right-hand window to bring to front once
  std::string drag_name;    ///< robot or obstacle being dragged
  double frame_ms = 0;      ///< the last frame, as the window measured it
  /// Headless --ui frames: plots are redrawn at every frame with new rows (the window redraws
  /// them at most every 100 ms of wall time while running), so each frame shows its own step's
  /// data, the same in every run.
  bool plots_every_frame = false;

  // View options, shared: set by the View panel (app/gui/view_panel.hpp), read by the world view.
  std::set<std::string> overlays = DefaultSceneOverlays();  ///< of the scene (View panel)
  bool legend = true;    ///< a legend of every mark drawn in the world view
  bool help = false;     ///< the help overlay (F1)
  bool present = false;  ///< presentation mode: the world view fills the window
  /// Where presentation mode's buttons ended last frame (logical pixels from the top; 0: none):
  /// the camera frames the formation below them.
  float present_bar_bottom = 0;
  /// Presentation mode's bar as last drawn (x0, y0, x1, y1): scene labels keep off it.
  ImVec4 present_bar;
  /// The presentation camera frames the formation outside presentation mode too.
  bool frame_formation = false;
  PresentationCamera camera;  ///< view-only: frames and follows the formation (app/render/camera)
  LegendState legend_state;   ///< the world legend's corner and whether it is collapsed
  UiSettings settings;        ///< UI scale and angle unit, kept between runs

  // The command table's window parts (app/gui/ui_menu.cpp, app/gui/ui_palette.cpp).
  std::string layout_report_path;  ///< `layout-report`: written at the end of the next frame
  /// This frame's plots (figure id, data area in logical pixels), for the layout report.
  std::vector<std::pair<std::string, ImVec4>> frame_plots;
  bool quit_requested = false;     ///< `quit`: the window closes after this frame
  bool about = false;              ///< the About box
  bool palette = false;            ///< the command palette (Ctrl+K)
  bool palette_focus = false;      ///< give the palette's field the keyboard on its next frame
  char palette_filter[256] = "";
  int palette_selected = 0;
  std::vector<std::string> recent_commands;  ///< newest first, run from the menu or palette
  std::string open_menu;                     ///< `menu NAME`: a top-level menu to open once
  /// The argument dialog of a command run from the menu or palette (none: "").
  std::string dialog_command;
  char dialog_args[3][1024] = {};
  std::string dialog_error;
};

/// One line of the command palette: a command or a tunable.
struct PaletteEntry {
  bool tunable = false;
  std::string name;    ///< the command or the tunable's key
  std::string detail;  ///< help, or the tunable's label and value (plain text)
  /// `detail` as label markup, drawn with its subscripts: a tunable's name is
  /// TunableLabel (app/gui/tunable_label.hpp), the name the Parameters panel shows.
  std::string detail_markup;
  std::string keys;
  int score = 0;  ///< lower first
};

/// The About box's text.
std::string AboutText();

class AppUi {
 public:
  /// The least share of the window's area the world view's drawing takes outside presentation
  /// mode (0.5 and a margin; presentation mode gives it all but the timeline's strip).
  static constexpr float kWorldViewShare = 0.54f;
  /// The least width, in font units (the window's pixels over the UI scale), of the two side
  /// panels together; with less beside the world view the window has two columns: the tabs
  /// with the control panel as the first, and the world view.
  static constexpr float kSidePanelsMin = 630.0f;
  enum class Layout { kThreeColumns, kNarrow, kPresentation };
  /// The layout of the last frame drawn.
  Layout layout() const { return layout_; }
  explicit AppUi(std::unique_ptr<sim::Session> session);
  /// Borrows a session owned by the caller (headless --ui frames); loading another scenario
  /// then makes the interface own the new one.
  explicit AppUi(sim::Session& borrowed);
  /// Stops recording the session (a borrowed one outlives the interface).
  ~AppUi();
  AppUi(const AppUi&) = delete;
  AppUi& operator=(const AppUi&) = delete;

  sim::Session& session() { return *session_; }
  /// Applied to every experiment of every session the interface runs (the current one, resets,
  /// and scenarios loaded later): bounded history, streaming of the rows to --out.
  void SetRunSetup(std::function<void(sim::Experiment&)> setup);
  UiState& state() { return state_; }
  const UiState& state() const { return state_; }
  const sim::Session& session() const { return *session_; }

  /// Advances the simulation for `wall_dt` seconds of real time at the chosen speed (GUI loop).
  void Advance(double wall_dt);
  /// Builds all windows for a display of `display` pixels. `interactive` = false draws the same
  /// panels without reading mouse or keyboard (headless --ui frames).
  void Draw(ImVec2 display, const Fonts& fonts, bool interactive);
  /// After ImGui::Render() of a frame Draw built: writes the `layout-report` asked for, from the
  /// frame's draw data.
  void AfterRender();
  /// With "whole run" on, adds the experiment's current bounds to the camera's union (headless
  /// runs that draw only a final snapshot call this while stepping).
  void TrackBounds();

  // ---- Commands: what buttons, keys and scripts do. Each returns "" or why it was refused,
  // and leaves a message in the status line. None of them can end the program.
  /// The world view back at the live end (the Timeline panel's `live`).
  std::string CmdLive();
  /// Writes the session record (everything done so far, with steps) to `path`.
  std::string CmdSaveSession(const std::string& path);
  /// Asks for a screenshot of the next frame (the window writes it).
  std::string CmdScreenshot(const std::string& path);
  // ---- Crash-safe sessions (app/gui/ui_journal.cpp): the journal of the record and its restore.
  /// Journals the record from now on into a new journal in `dir` (sim::JournalDir()), flushed
  /// at every event, so a crash leaves a session `formsim replay` reproduces.
  void StartJournal(const std::string& dir);
  /// Per frame: the journal notes the step reached (at most once a second).
  void NoteJournalStep();
  /// Ends the journal; `remove`: deletes it (a clean exit, or the session file was written).
  void CloseJournal(bool remove);
  /// Offers the newest unfinished session in `dir` (a journal whose window is gone): a banner
  /// with Restore and Discard, never restored by itself.
  void FindUnfinishedSessions(const std::string& dir);
  /// Replays the offered unfinished session and goes on from it (its journal is then removed).
  std::string CmdRestoreSession();
  /// Deletes the offered unfinished session's journal.
  std::string CmdDiscardSession();
  /// The unfinished sessions offered (newest first).
  const std::vector<sim::RecoveredSession>& unfinished_sessions() const { return unfinished_; }
  /// Runs one script action "ACTION [ARGS]" (see `formsim gui --script`) through the command
  /// table. Returns "" or the reason it was refused.
  std::string RunScriptAction(const std::string& line);
  /// Runs a row of the command table with its arguments as text: checks that it is enabled,
  /// parses the arguments, runs it. Returns "" or the reason, also shown in the status line.
  std::string RunCommand(const Command& cmd, const std::string& args, CommandSource source);
  /// Runs the command bound to `key` ("space", "F1", "Ctrl+Z"; see Command::keys); "" when
  /// none is bound.
  std::string PressKey(const std::string& key);
  /// Opens the command palette with `filter` typed in.
  std::string CmdPalette(const std::string& filter);
  /// What the palette lists for `filter`, best first.
  std::vector<PaletteEntry> PaletteEntries(const std::string& filter) const;
  /// Where the menu bar drew each command's item in the last frame its menu was open (tests
  /// click them).
  const std::map<std::string, std::pair<ImVec2, ImVec2>>& menu_items() const { return menu_items_; }
  /// True while work goes on in the background (pins replaying, a Monte Carlo, the timeline
  /// catching up): the script action `wait` holds the script until it is done.
  bool Busy() const;

  /// The record of the session so far (written by CmdSaveSession and `--session`).
  const sim::SessionRecord& record() const { return record_; }
  /// With `formsim gui --session FILE`: where "Save session" writes by default.
  void SetSessionFile(const std::string& path);
  /// Called after each file the user asked for is written (save, save-session, screenshot,
  /// export-figures), with its path and MIME type: the browser page turns it into a download.
  void SetFileWrittenHook(
      std::function<void(const std::string& path, const std::string& mime)> hook) {
    file_written_hook_ = std::move(hook);
  }
  void NoteFileWritten(const std::string& path, const std::string& mime) const {
    if (file_written_hook_) file_written_hook_(path, mime);
  }
  /// File/Open… calls `hook` instead of asking for a path (the browser page shows its file
  /// picker, which then runs `open PATH` with the picked file's copy).
  void SetPickFileHook(std::function<void()> hook) { pick_file_hook_ = std::move(hook); }

  // ---- The panels (app/gui/panel.hpp) and what the window shares with them.
  /// The panel of type P the window has now (the kind's own panel, or one of the window's), or
  /// null: a formation scenario has a FormationEditorPanel, others none.
  template <class P>
  P* Find() const {
    return ctx_.Find<P>();
  }
  /// The first panel with something open that Esc closes (null: none).
  Panel* PanelToDismiss() const;
  /// The status line's message (an error is shown in red, also over the world view).
  void SetStatus(const std::string& message, bool error = false);
  /// Replaces the live run by `change` (a structural change, a branch): when `change` succeeds
  /// ("") the old run's history row is kept with `status`. Returns what `change` returned.
  std::string ReplaceRun(const std::string& status, const std::function<std::string()>& change);

 private:
  void HandleKeys();
  /// `layout-report`: what a person sees of this frame (app/gui/frame_audit.hpp), as JSON.
  void WriteLayoutReport();
  ImVec2 frame_display_;  ///< this frame's window size, logical
  Layout layout_ = Layout::kThreeColumns;
  /// The height the world window takes besides its drawing: the timeline's strip.
  float WorldWindowChrome() const;
  ImVec4 world_rect_;     ///< this frame's world view drawing area (x0, y0, x1, y1); none: empty
  WorldViewReport world_report_;  ///< what the last world view drawing placed
  FocusSet frame_focus_;          ///< this frame's robots and recent trails (camera, world view)
  /// The menu bar, generated from the command table; returns its height.
  float DrawMenuBar();
  void DrawMenuItem(const Command& cmd);
  /// Opens the argument dialog of `cmd` (commands with arguments, from the menu or palette).
  void OpenCommandDialog(const Command& cmd);
  void DrawCommandDialog();
  void DrawPalette(ImVec2 display);
  void DrawAbout();
  /// Per frame: collects finished pin replays, Monte Carlo results, the timeline's progress.
  void UpdateBackground();
  void StartRecording(const std::vector<sim::Override>& cli, long step);
  void DropScenarioState();  ///< pins, Monte Carlo, timeline: on loading another scenario
  /// The experiment the world view shows: the timeline's replay, or the live run.
  const sim::Experiment& ShownExperiment() const;
  /// The kind's own panel for the experiment now: made, kept or dropped (MakeKindPanel).
  void SyncKindPanel();
  /// The context handed to the panels, then the window's own panels, made once.
  void MakePanels();
  /// Makes a panel of type P with the window's context and keeps it.
  template <class P>
  P* AddPanel() {
    auto panel = std::make_unique<P>(ctx_);
    P* raw = panel.get();
    panels_.push_back(std::move(panel));
    return raw;
  }
  /// Replaces the session after a successful load (keeps view options, resets per-run state).
  void Adopt(std::unique_ptr<sim::Session> session, const std::string& message);
  void SyncScenarioFields();
  void DrawControlPanel(const Fonts& fonts, bool interactive);
  void DrawMessagesSection();
  void DrawWorldWindow(ImVec2 pos, ImVec2 size, const Fonts& fonts, bool interactive);
  void DrawWorldMouse(const View& view);
  /// The tabbed window (Lesson, Plots, Tables, History, Summary); `with_controls`: the control
  /// panel as its first tab (the narrow layout).
  void DrawPlotsWindow(ImVec2 pos, ImVec2 size, const Fonts& fonts, bool with_controls = false);
  void UpdateView(ImVec2 min, ImVec2 max);

  std::map<std::string, std::pair<ImVec2, ImVec2>> menu_items_;
  /// The window's panels (the Lesson), and the experiment kind's own panel (null for a kind
  /// without one): drawn where the layout puts them.
  std::vector<std::unique_ptr<Panel>> panels_;
  std::unique_ptr<Panel> kind_panel_;
  std::function<void(const std::string&, const std::string&)> file_written_hook_;
  std::function<void()> pick_file_hook_;
  PanelContext ctx_;  ///< what every panel gets of the window (refers to the members above)
  TimelinePanel* timeline_ = nullptr;      ///< one of panels_: every window has one
  HistoryPanel* history_ = nullptr;        ///< one of panels_: every window has one
  ComparePanel* compare_ = nullptr;        ///< one of panels_: every window has one
  ParametersPanel* parameters_ = nullptr;  ///< one of panels_: every window has one
  PlotsPanel* plots_ = nullptr;            ///< one of panels_: every window has one
  RunPanel* run_ = nullptr;                ///< one of panels_: every window has one
  ScenarioPanel* scenario_ = nullptr;      ///< one of panels_: every window has one
  TablesPanel* tables_ = nullptr;          ///< one of panels_: every window has one
  ViewPanel* view_ = nullptr;              ///< one of panels_: every window has one
  std::function<void(sim::Experiment&)> run_setup_;
  std::unique_ptr<sim::Session> owned_;
  sim::Session* session_ = nullptr;
  UiState state_;
  AutoFit auto_fit_;

  // The session record (every panel notes what it does in it) and its crash-safe journal.
  sim::SessionRecord record_;
  std::string session_file_;
  std::unique_ptr<sim::SessionJournal> journal_;   ///< the window's crash-safe journal
  std::vector<sim::RecoveredSession> unfinished_;  ///< offered for restore, newest first
  bool journal_error_shown_ = false;
  /// The banner offering to restore an unfinished session (top of the control panel).
  void DrawRestoreBanner();
};

/// Copies `s` into the text buffer `dst` of `n` bytes (an ImGui input field), cut to fit.
void CopyString(char* dst, std::size_t n, const std::string& s);

}  // namespace formsim::app
