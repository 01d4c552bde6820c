#include "app/gui/ui.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "app/gui/compare_panel.hpp"
#include "app/gui/formation_editor_panel.hpp"
#include "app/gui/frame_audit.hpp"
#include "app/gui/history_panel.hpp"
#include "app/gui/layout_audit.hpp"
#include "app/gui/lesson_panel.hpp"
#include "app/gui/parameters_panel.hpp"
#include "app/gui/plots_panel.hpp"
#include "app/gui/run_panel.hpp"
#include "app/gui/scenario_panel.hpp"
#include "app/gui/tables_panel.hpp"
#include "app/gui/timeline_panel.hpp"
#include "app/gui/view_panel.hpp"
#include "app/render/imgui_canvas.hpp"
#include "app/render/long_text.hpp"
#include "sim/core/json.hpp"
#include "sim/core/number_format.hpp"
#include "sim/scenario/scenario_files.hpp"

namespace fs = std::filesystem;

namespace formsim::app {


namespace {





}  // namespace

AppUi::AppUi(std::unique_ptr<sim::Session> session) : owned_(std::move(session)) {
  session_ = owned_.get();
  MakePanels();
  SyncScenarioFields();
  StartRecording(session_->cli_overrides(), 0);
  history_->LoadFor(session_->file());
}

AppUi::AppUi(sim::Session& borrowed) : session_(&borrowed) {
  MakePanels();
  SyncScenarioFields();
  StartRecording(session_->cli_overrides(), 0);
  history_->LoadFor(session_->file());
}

AppUi::~AppUi() {
  session_->SetObserver(nullptr);
}

void AppUi::SetRunSetup(std::function<void(sim::Experiment&)> setup) {
  run_setup_ = std::move(setup);
  session_->SetRunSetup(run_setup_);
}

void AppUi::MakePanels() {
  ctx_.session = [this]() -> sim::Session& { return *session_; };
  ctx_.record = &record_;
  ctx_.state = &state_;
  ctx_.set_status = [this](const std::string& message, bool error) { SetStatus(message, error); };
  ctx_.shown = [this]() -> const sim::Experiment& { return ShownExperiment(); };
  ctx_.adopt = [this](std::unique_ptr<sim::Session> session, const std::string& message) {
    Adopt(std::move(session), message);
  };
  ctx_.scenario_changed = [this] {
    SyncScenarioFields();
    SyncKindPanel();  // the file may now hold another kind
  };
  ctx_.run = [this](const std::string& line) { return RunScriptAction(line); };
  ctx_.file_written = [this](const std::string& path, const std::string& mime) {
    NoteFileWritten(path, mime);
  };
  ctx_.replace_run = [this](const std::string& status, const std::function<std::string()>& change) {
    return ReplaceRun(status, change);
  };
  ctx_.panels = &panels_;
  ctx_.kind_panel = &kind_panel_;
  // The window's panels, in the order Esc asks them (PanelToDismiss).
  timeline_ = AddPanel<TimelinePanel>();
  history_ = AddPanel<HistoryPanel>();
  compare_ = AddPanel<ComparePanel>();
  plots_ = AddPanel<PlotsPanel>();
  scenario_ = AddPanel<ScenarioPanel>();
  parameters_ = AddPanel<ParametersPanel>();
  run_ = AddPanel<RunPanel>();
  view_ = AddPanel<ViewPanel>();
  tables_ = AddPanel<TablesPanel>();
  AddPanel<LessonPanel>();
  SyncKindPanel();
}

void AppUi::SyncKindPanel() {
  if (!IsKindPanelFor(kind_panel_.get(), session_->exp()))
    kind_panel_ = MakeKindPanel(ctx_, session_->exp());
}

Panel* AppUi::PanelToDismiss() const {
  if (kind_panel_ && kind_panel_->Dismissable()) return kind_panel_.get();
  for (const auto& panel : panels_)
    if (panel->Dismissable()) return panel.get();
  return nullptr;
}

std::string AppUi::ReplaceRun(const std::string& status,
                              const std::function<std::string()>& change) {
  auto row = history_->PendingRow(status);
  const std::string err = change();
  if (!err.empty()) return err;
  if (row) history_->Add(std::move(*row));
  return "";
}

std::string AppUi::CmdLive() {
  return timeline_->CmdLive();
}

void AppUi::SetStatus(const std::string& message, bool error) {
  state_.status = message;
  state_.status_is_error = error;
  state_.status_time = ImGui::GetCurrentContext() != nullptr ? ImGui::GetTime() : 0.0;
}

// Per-scenario fields of the interface, after a load or reload.
void AppUi::SyncScenarioFields() {
  const std::string current = session_->file();
  scenario_->SyncScenario();
  if (session_file_.empty())
    CopyString(state_.session_path, sizeof(state_.session_path),
               fs::path(current).stem().string() + "_session.yaml");
  plots_->Clear();
  state_.follow = -1;
  state_.auto_fit = true;
  state_.fit_now = true;
  run_->SyncScenario();
  auto_fit_.Reset();
}

void AppUi::Adopt(std::unique_ptr<sim::Session> session, const std::string& message) {
  // The old scenario's last run goes into its history, kept for when it is opened again.
  history_->Shelve(session_->file());
  DropScenarioState();
  const long step = session_->exp().steps();
  if (run_setup_) {
    session_->exp().mutable_recorder().AbandonStream();
    session->SetRunSetup(run_setup_);
  }
  session_->SetObserver(nullptr);
  owned_ = std::move(session);
  session_ = owned_.get();
  SyncScenarioFields();
  SyncKindPanel();
  StartRecording({}, step);
  history_->LoadFor(session_->file());
  SetStatus(message);
}

// ---- commands ----

void AppUi::Advance(double wall_dt) {
  run_->Advance(wall_dt);
}












std::string AppUi::CmdScreenshot(const std::string& path) {
  state_.screenshot_requested = true;
  state_.screenshot_path = path;
  return "";
}




std::string AppUi::RunScriptAction(const std::string& line) {
  std::string action, args;
  SplitCommandLine(line, &action, &args);
  const Command* cmd = FindCommand(action);
  if (cmd == nullptr) {
    std::string names;
    for (const std::string& n : ClosestCommands(action)) names += (names.empty() ? "" : ", ") + n;
    const std::string shown = action.size() > 80 ? action.substr(0, 80) + "…" : action;
    const std::string why = "unknown action '" + shown + "' (closest: " + names +
                            "; `formsim gui --list-commands` lists them all)";
    SetStatus(why, true);
    return why;
  }
  return RunCommand(*cmd, args, CommandSource::kScript);
}

std::string AppUi::RunCommand(const Command& cmd, const std::string& args, CommandSource source) {
  SyncKindPanel();
  if (cmd.disabled) {
    if (const std::string why = cmd.disabled(*this); !why.empty()) {
      SetStatus(cmd.name + ": " + why, true);
      return state_.status;
    }
  }
  CommandArgs parsed;
  if (std::string err = ParseCommandArgs(cmd, args, this, &parsed); !err.empty()) {
    SetStatus(err, true);
    return err;
  }
  if (source == CommandSource::kMenu || source == CommandSource::kPalette) {
    auto& recent = state_.recent_commands;
    recent.erase(std::remove(recent.begin(), recent.end(), cmd.name), recent.end());
    recent.insert(recent.begin(), cmd.name);
    if (recent.size() > 8) recent.resize(8);
  }
  const std::string before = state_.status;
  std::string err;
  try {
    err = cmd.run(*this, parsed, source);
  } catch (const std::exception& e) {
    err = cmd.name + ": " + e.what();
  }
  // Every refusal reaches the status line, also from commands that do not set it themselves.
  if (!err.empty() && (state_.status == before || !state_.status_is_error)) SetStatus(err, true);
  return err;
}

std::string AppUi::PressKey(const std::string& key) {
  for (const Command& c : Commands())
    for (const std::string& k : c.keys)
      if (k == key) return RunCommand(c, c.key_args, CommandSource::kKey);
  return "";
}


void AppUi::HandleKeys() {
  ImGuiIO& io = ImGui::GetIO();
  // Called after this frame's widgets: typing into a field (or a field that a click activated
  // in this very frame, which io.WantTextInput does not know yet) never reaches a shortcut; nor
  // does a key in the frame between a double-click opening a value entry and its taking the
  // keyboard.
  if (io.WantTextInput || io.WantCaptureKeyboard || ImGui::IsAnyItemActive() ||
      parameters_->EntryDrawnThisFrame())
    return;
  if (io.KeyCtrl) {
    // The window's backend (GLFW) indexes letter keys by their upper-case ASCII code.
    for (int c = 'A'; c <= 'Z'; ++c)
      if (ImGui::IsKeyPressed(c, false))
        PressKey(std::string("Ctrl+") + (io.KeyShift ? "Shift+" : "") + static_cast<char>(c));
    return;  // Ctrl+letter is never a plain shortcut
  }
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) PressKey("Esc");
  // ImGui 1.86 maps only a few named keys, so shortcuts read the typed characters.
  for (int i = 0; i < io.InputQueueCharacters.Size; ++i) {
    const ImWchar ch = io.InputQueueCharacters[i];
    if (ch == ' ') PressKey("space");
    else if (ch > ' ' && ch < 127) PressKey(std::string(1, static_cast<char>(ch)));
  }
}

void AppUi::Draw(ImVec2 display, const Fonts& fonts, bool interactive) {
  frame_display_ = display;
  world_rect_ = ImVec4();
  state_.frame_plots.clear();
  UpdateBackground();
  SyncKindPanel();
  // Over everything else: the palette, a command's argument dialog, the About box.
  auto overlays = [&] {
    DrawCommandDialog();
    DrawAbout();
    DrawPalette(display);
    // A slider no longer held ends its drag: its next edit is a new undo step.
    if (!ImGui::IsAnyItemActive()) state_.gesture_key.clear();
    if (interactive) HandleKeys();
  };
  if (state_.present) {
    // Presentation: the world view fills the window; a small bar keeps the essentials.
    layout_ = Layout::kPresentation;
    DrawWorldWindow(ImVec2(0, 0), display, fonts, interactive);
    view_->DrawPresentationBar(ImVec2(0, 0), display);
    if (state_.help) view_->DrawHelpOverlay(ImVec2(0, 0), display);
    overlays();
    return;
  }
  const float top = DrawMenuBar();
  const float h = std::max(1.0f, display.y - top);
  // The world view keeps at least kWorldViewShare of the window, whatever the UI scale (a
  // lecture at scale 2 shows the robots first): three columns when both side panels still fit
  // beside it, else two, the control panel a tab beside the plots.
  const float world_h = std::max(1.0f, h - WorldWindowChrome());
  const float world_w_min = std::min(display.x, kWorldViewShare * display.x * display.y / world_h);
  const float side = display.x - world_w_min;
  layout_ = side >= kSidePanelsMin ? Layout::kThreeColumns : Layout::kNarrow;
  if (layout_ == Layout::kNarrow) {
    const float left_w = std::max(1.0f, std::min(std::clamp(display.x * 0.40f, 250.0f, 420.0f), side));
    DrawPlotsWindow(ImVec2(0, top), ImVec2(left_w, h), fonts, true);
    DrawWorldWindow(ImVec2(left_w, top), ImVec2(display.x - left_w, h), fonts, interactive);
    if (state_.help) view_->DrawHelpOverlay(ImVec2(left_w, top), display);
    overlays();
    return;
  }
  const float left_w = std::clamp(std::floor(side * 0.42f), 290.0f, 400.0f);
  const float right_w = std::clamp(side - left_w, 340.0f, 640.0f);
  const float mid_w = std::max(200.0f, display.x - left_w - right_w);

  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(left_w, h));
  // No background of its own: the frame is cleared to the window colour first (a software
  // rasteriser then shades a third of the screen less).
  ImGui::Begin("formsim", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoBackground);
  DrawControlPanel(fonts, interactive);
  ImGui::End();

  DrawWorldWindow(ImVec2(left_w, top), ImVec2(mid_w, h), fonts, interactive);
  DrawPlotsWindow(ImVec2(left_w + mid_w, top), ImVec2(display.x - left_w - mid_w, h), fonts);
  if (state_.help) view_->DrawHelpOverlay(ImVec2(left_w, top), ImVec2(left_w + mid_w, display.y));
  overlays();
}

void AppUi::AfterRender() {
  if (!state_.layout_report_path.empty()) WriteLayoutReport();
}

namespace {

sim::Json RectJson(const ImVec4& r) {
  sim::Json a = sim::Json::Array();
  for (float v : {r.x, r.y, r.z - r.x, r.w - r.y}) a.Push(sim::Json(std::round(10.0 * v) / 10.0));
  return a;
}

// One list of findings: each with its window, text, rectangle [x, y, w, h] in pixels, and what
// `other` and `value` mean for the list.
sim::Json FindingsJson(const std::vector<AuditFinding>& list, const char* other, const char* value) {
  sim::Json out = sim::Json::Array();
  for (const AuditFinding& f : list) {
    sim::Json e = sim::Json::Object();
    e["widget"] = sim::Json(f.window);
    e["text"] = sim::Json(f.text);
    e["rect"] = RectJson(f.rect);
    if (other) e[other] = sim::Json(f.other);
    if (value) e[value] = sim::Json(std::round(100.0 * f.value) / 100.0);
    out.Push(e);
  }
  return out;
}

}  // namespace

void AppUi::WriteLayoutReport() {
  const std::string path = state_.layout_report_path;
  state_.layout_report_path.clear();
  const ImDrawData* draw = ImGui::GetDrawData();
  if (draw == nullptr || !draw->Valid) {
    SetStatus("layout-report: the frame has no draw data", true);
    return;
  }
  const ImVec2 display = frame_display_;
  // The window in pixels: the layout itself is in font units (pixels over the UI scale).
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x;
  AuditMarks marks;
  marks.pixel_scale = scale;
  marks.ui_scale = state_.settings.ui_scale;
  marks.display = display;
  marks.world_view = world_rect_;
  marks.clear_colour = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  for (const auto& r : world_report_.robots) marks.robots.push_back({r.name, r.centre, r.radius});
  if (state_.legend && world_report_.legend_box.z > world_report_.legend_box.x)
    marks.over_world.push_back({"legend", world_report_.legend_box});
  if (world_report_.scale_bar_box.z > world_report_.scale_bar_box.x)
    marks.over_world.push_back({"scale bar", world_report_.scale_bar_box});
  for (const auto& [id, rect] : state_.frame_plots) marks.plots.push_back({id, rect});
  const FrameAudit audit = AuditFrame(*draw, marks);

  sim::Json report = sim::Json::Object();
  sim::Json window = sim::Json::Array();
  window.Push(sim::Json(std::round(display.x * scale)));
  window.Push(sim::Json(std::round(display.y * scale)));
  report["window"] = window;
  report["ui_scale"] = sim::Json(static_cast<double>(state_.settings.ui_scale));
  report["layout"] = sim::Json(layout_ == Layout::kPresentation ? "presentation"
                               : layout_ == Layout::kNarrow      ? "narrow"
                                                                 : "three columns");
  report["theme"] = sim::Json(GetTheme(state_.theme).name);
  // Cut text: lines whose items reach past a window's edge (read before the frame's end), and
  // glyphs cut at a clip edge (from the draw data).
  sim::Json clipped = sim::Json::Array();
  for (const ClippedText& c : FindClippedText()) {
    sim::Json e = sim::Json::Object();
    e["widget"] = sim::Json(c.widget);
    e["text"] = sim::Json(c.text);
    e["available"] = sim::Json(static_cast<double>(c.available));
    e["needed"] = sim::Json(static_cast<double>(c.needed));
    clipped.Push(e);
  }
  const sim::Json cut = FindingsJson(audit.cut, nullptr, nullptr);
  for (const sim::Json& e : cut.items()) clipped.Push(e);
  report["clipped"] = clipped;
  report["overlaps"] = FindingsJson(audit.overlaps, "over", nullptr);
  report["small_text"] = FindingsJson(audit.small_text, nullptr, "px");
  report["low_contrast"] = FindingsJson(audit.low_contrast, "colours", "ratio");
  report["small_plots"] = FindingsJson(audit.small_plots, nullptr, "px");
  report["world_view_share"] = sim::Json(std::round(1000.0 * audit.world_view_share) / 1000.0);
  report["text_runs"] = sim::Json(static_cast<double>(audit.text_runs));
  report["world_labels"] = sim::Json(static_cast<double>(world_report_.labels));
  report["overlapping_labels"] = sim::Json(static_cast<double>(world_report_.overlapping_labels));
  report["formation_fraction"] = sim::Json(world_report_.formation_fraction);
  std::ofstream f(path);
  f << report.Dump() << "\n";
  if (!f) SetStatus("layout-report: cannot write " + path, true);
}

void AppUi::DrawControlPanel(const Fonts& fonts, bool interactive) {
  (void)interactive;
  DrawRestoreBanner();
  if (ImGui::CollapsingHeader("Scenario", ImGuiTreeNodeFlags_DefaultOpen)) scenario_->Draw(fonts);
  if (ImGui::CollapsingHeader("Run", ImGuiTreeNodeFlags_DefaultOpen)) run_->Draw(fonts);
  if (ImGui::CollapsingHeader("Compare", ImGuiTreeNodeFlags_DefaultOpen)) compare_->Draw(fonts);
  SyncKindPanel();  // a button above may have loaded another scenario
  if (kind_panel_) kind_panel_->Draw(fonts);
  parameters_->Draw(fonts);
  if (ImGui::CollapsingHeader("View")) view_->Draw(fonts);
  DrawMessagesSection();
}





void AppUi::DrawMessagesSection() {
  const auto& rejected = session_->rejected();
  const auto& events = session_->exp().events().list();
  const std::string title = sim::Sprintf("Messages (%zu rejected, %zu events)###messages",
                                         rejected.size(), events.size());
  if (!state_.status.empty()) {
    if (state_.status_is_error) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.75f, 0.1f, 0.1f, 1));
    LongTextWrapped("status", state_.status, 600);  // any length (app/render/long_text.hpp)
    if (state_.status_is_error) ImGui::PopStyleColor();
  }
  const ImGuiTreeNodeFlags open = rejected.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen;
  if (!ImGui::CollapsingHeader(title.c_str(), open)) return;
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.75f, 0.1f, 0.1f, 1));
  for (auto it = rejected.rbegin(); it != rejected.rend() && it - rejected.rbegin() < 8; ++it)
    ImGui::TextWrapped("%s", Shorten(*it, 600).c_str());
  ImGui::PopStyleColor();
  const std::size_t first = events.size() > 12 ? events.size() - 12 : 0;
  for (std::size_t i = events.size(); i-- > first;)
    ImGui::TextWrapped("%s",
                       sim::Sprintf("%.2f s %s %s: %s", events[i].time, events[i].kind.c_str(),
                                    Shorten(events[i].robots, 200).c_str(),
                                    Shorten(events[i].message, 400).c_str())
                           .c_str());
}

void CopyString(char* dst, std::size_t n, const std::string& s) {
  if (n == 0) return;
  dst[s.copy(dst, n - 1)] = '\0';  // cut to the buffer, always terminated
}

}  // namespace formsim::app
