#include "app/gui/ui.hpp"
#include "app/render/imgui_canvas.hpp"
#include "app/render/long_text.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "app/gui/formation_editor_panel.hpp"
#include "app/gui/compare_panel.hpp"
#include "app/gui/history_panel.hpp"
#include "app/gui/plots_panel.hpp"
#include "app/gui/run_panel.hpp"
#include "app/gui/tables_panel.hpp"
#include "app/gui/lesson_panel.hpp"
#include "app/gui/timeline_panel.hpp"
#include "sim/core/number_format.hpp"
#include "sim/scenario/scenario_files.hpp"

namespace fs = std::filesystem;

namespace formsim::app {


namespace {


void CopyString(char* dst, std::size_t n, const std::string& s) {
  std::snprintf(dst, n, "%s", s.c_str());
}

// What the scenario list offers: the shipped scenarios, then the lessons.
std::vector<std::string> ShippedAndLessons() {
  std::vector<std::string> out = sim::ShippedScenarios();
  for (std::string& f : sim::ShippedLessons()) out.push_back(std::move(f));
  return out;
}

// A list entry's name: its stem, lessons marked as such.
std::string ListName(const std::string& file) {
  const fs::path p(file);
  const std::string stem = p.stem().string();
  return p.parent_path().filename() == "lessons" ? "lesson: " + stem : stem;
}

}  // namespace

AppUi::AppUi(std::unique_ptr<sim::Session> session) : owned_(std::move(session)) {
  session_ = owned_.get();
  MakePanels();
  shipped_ = ShippedAndLessons();
  SyncScenarioFields();
  StartRecording(session_->cli_overrides(), 0);
  history_->LoadFor(session_->file());
}

AppUi::AppUi(sim::Session& borrowed) : session_(&borrowed) {
  MakePanels();
  shipped_ = ShippedAndLessons();
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
  ctx_.run = [this](const std::string& line) { return RunScriptAction(line); };
  ctx_.replace_run = [this](const std::string& status, const std::function<std::string()>& change) {
    return ReplaceRun(status, change);
  };
  ctx_.panels = &panels_;
  ctx_.kind_panel = &kind_panel_;
  auto timeline = std::make_unique<TimelinePanel>(ctx_);
  timeline_ = timeline.get();
  panels_.push_back(std::move(timeline));
  auto history = std::make_unique<HistoryPanel>(ctx_);
  history_ = history.get();
  panels_.push_back(std::move(history));
  auto compare = std::make_unique<ComparePanel>(ctx_);
  compare_ = compare.get();
  panels_.push_back(std::move(compare));
  auto plots = std::make_unique<PlotsPanel>(ctx_);
  plots_ = plots.get();
  panels_.push_back(std::move(plots));
  auto run = std::make_unique<RunPanel>(ctx_);
  run_ = run.get();
  panels_.push_back(std::move(run));
  auto tables = std::make_unique<TablesPanel>(ctx_);
  tables_ = tables.get();
  panels_.push_back(std::move(tables));
  panels_.push_back(std::make_unique<LessonPanel>(ctx_));
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
  // The loaded file's entry, or none (-1) for a file of the user's.
  shipped_index_ = -1;
  for (std::size_t i = 0; i < shipped_.size(); ++i)
    if (fs::path(shipped_[i]).filename() == fs::path(current).filename())
      shipped_index_ = static_cast<int>(i);
  CopyString(state_.open_path, sizeof(state_.open_path), current);
  CopyString(state_.save_path, sizeof(state_.save_path),
             fs::path(current).stem().string() + "_tuned.yaml");
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






std::string AppUi::CmdReload() {
  auto row = history_->PendingRow("reloaded");
  const std::string err = session_->Reload();
  if (!err.empty()) {
    SetStatus(err, true);
    return err;
  }
  if (row) history_->Add(std::move(*row));
  SyncScenarioFields();
  SyncKindPanel();  // the file may now hold another kind
  SetStatus("reloaded " + session_->file());
  return "";
}

std::string AppUi::CmdLoad(const std::string& name_or_path) {
  std::string file;
  try {
    file = sim::ResolveScenario(name_or_path);
  } catch (const std::exception& e) {
    SetStatus(std::string("cannot load: ") + e.what(), true);
    return state_.status;
  }
  return CmdOpen(file);
}

std::string AppUi::CmdOpen(const std::string& path) {
  // Copy first: `path` may refer to state that the new session replaces.
  const std::string file = path;
  try {
    Adopt(std::make_unique<sim::Session>(file, std::vector<sim::Override>{}), "loaded " + file);
  } catch (const std::exception& e) {
    SetStatus(std::string("cannot load, the current scenario stays: ") + e.what(), true);
    return state_.status;
  }
  return "";
}

std::string AppUi::CmdSave(const std::string& path, bool overwrite) {
  if (path.empty()) {
    SetStatus("save: give a file name", true);
    return state_.status;
  }
  try {
    std::string note;
    if (session_->Save(path, overwrite, &note) == sim::Session::SaveResult::kNeedsConfirmation) {
      confirm_overwrite_ = true;
      SetStatus(path + " exists: confirm to overwrite");
      return "";
    }
    std::string also;
    if (!history_->history().empty()) {
      // The history goes beside the scenario and comes back when it is opened.
      const std::string hist = sim::RunHistory::PathFor(path);
      try {
        history_->history().Save(hist);
        also = ", history in " + hist;
      } catch (const std::exception& e) {
        also = "; the history was not saved: " + std::string(e.what());
      }
    }
    SetStatus("saved " + path + (note.empty() ? "" : " (" + note + ")") + also);
  } catch (const std::exception& e) {
    SetStatus(std::string("save failed: ") + e.what(), true);
    return state_.status;
  }
  return "";
}

std::string AppUi::CmdEdit(const std::string& key, const std::string& value, bool continues_drag) {
  const std::string err = session_->Edit(key, value, "GUI edit", continues_drag);
  if (!err.empty()) SetStatus("edit " + key + "=" + value + " refused: " + err, true);
  return err;
}

std::string AppUi::CmdAction(const std::string& id) {
  const std::string err = session_->Action(id);
  if (!err.empty()) SetStatus(err, true);
  else SetStatus("action " + id);
  return err;
}

std::string AppUi::CmdScreenshot(const std::string& path) {
  state_.screenshot_requested = true;
  state_.screenshot_path = path;
  return "";
}

std::string AppUi::CmdUndo() {
  const std::string text = session_->UndoText();
  const std::string err = session_->Undo();
  SetStatus(err.empty() ? "undo " + text : err, !err.empty() && session_->can_undo());
  return err;
}

std::string AppUi::CmdRedo() {
  const std::string text = session_->RedoText();
  const std::string err = session_->Redo();
  SetStatus(err.empty() ? "redo " + text : err, !err.empty() && session_->can_redo());
  return err;
}

std::string AppUi::CmdRevert(const std::string& key) {
  const std::string loaded = session_->LoadedValue(key);
  if (loaded.empty()) {
    const std::string why = "revert: no tunable '" + key + "'";
    SetStatus(why, true);
    return why;
  }
  const std::string err = session_->Edit(key, loaded, "revert");
  if (!err.empty())
    SetStatus("revert " + key + " refused: " + err, true);
  else
    SetStatus("reverted " + key + " to " + loaded);
  return err;
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
      state_.value_entry.DrawnThisFrame())
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
    DrawWorldWindow(ImVec2(0, 0), display, fonts, interactive);
    DrawPresentationBar(ImVec2(0, 0), display);
    if (state_.help) DrawHelpOverlay(ImVec2(0, 0), display);
    overlays();
    return;
  }
  const float top = DrawMenuBar();
  const float left_w = std::clamp(display.x * 0.24f, 290.0f, 400.0f);
  const float right_w = std::clamp(display.x * 0.34f, 340.0f, 640.0f);
  const float mid_w = std::max(200.0f, display.x - left_w - right_w);
  const float h = std::max(1.0f, display.y - top);

  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(left_w, h));
  ImGui::Begin("formsim", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  DrawControlPanel(fonts, interactive);
  ImGui::End();

  DrawWorldWindow(ImVec2(left_w, top), ImVec2(mid_w, h), fonts, interactive);
  DrawPlotsWindow(ImVec2(left_w + mid_w, top), ImVec2(display.x - left_w - mid_w, h), fonts);
  if (state_.help) DrawHelpOverlay(ImVec2(left_w, top), ImVec2(left_w + mid_w, display.y));
  overlays();
}

void AppUi::DrawControlPanel(const Fonts& fonts, bool interactive) {
  (void)interactive;
  DrawRestoreBanner();
  if (ImGui::CollapsingHeader("Scenario", ImGuiTreeNodeFlags_DefaultOpen)) DrawScenarioSection();
  if (ImGui::CollapsingHeader("Run", ImGuiTreeNodeFlags_DefaultOpen)) run_->Draw(fonts);
  if (ImGui::CollapsingHeader("Compare", ImGuiTreeNodeFlags_DefaultOpen)) compare_->Draw(fonts);
  SyncKindPanel();  // a button above may have loaded another scenario
  if (kind_panel_) kind_panel_->Draw(fonts);
  DrawParamSection();
  if (ImGui::CollapsingHeader("View")) DrawViewSection();
  DrawMessagesSection();
}

void AppUi::DrawScenarioSection() {
  const sim::ExperimentSetup& setup = session_->exp().setup();
  LongTextWrapped("name", setup.name, 300);  // texts of any length (app/render/long_text.hpp)
  if (!setup.description.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    LongTextWrapped("description", setup.description);
    ImGui::PopStyleColor();
  }
  if (!shipped_.empty()) {
    const std::string preview =
        shipped_index_ >= 0 ? ListName(shipped_[shipped_index_]) : std::string("(a file of yours)");
    ImGui::SetNextItemWidth(-70);
    if (ImGui::BeginCombo("##shipped", preview.c_str())) {
      for (std::size_t i = 0; i < shipped_.size(); ++i) {
        const std::string name = ListName(shipped_[i]);
        if (ImGui::Selectable(name.c_str(), static_cast<int>(i) == shipped_index_))
          shipped_index_ = static_cast<int>(i);
      }
      ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (ImGui::Button("Load") && shipped_index_ >= 0) CmdOpen(shipped_[shipped_index_]);
  }
  ImGui::SetNextItemWidth(-70);
  ImGui::InputText("##open", state_.open_path, sizeof(state_.open_path));
  ImGui::SameLine();
  if (ImGui::Button("Open")) CmdOpen(state_.open_path);
  if (ImGui::Button("Reload file")) CmdReload();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Reload from disk, dropping the tuned values");

  ImGui::SetNextItemWidth(-70);
  ImGui::InputText("##save", state_.save_path, sizeof(state_.save_path));
  ImGui::SameLine();
  if (ImGui::Button("Save")) CmdSave(state_.save_path, false);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Write the scenario with the tuned values: the file's own text, comments\n"
                      "and layout, with only the changed values rewritten");
  if (confirm_overwrite_) ImGui::OpenPopup("Overwrite?");
  if (ImGui::BeginPopupModal("Overwrite?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    const bool shipped = sim::Session::IsShipped(state_.save_path);
    ImGui::Text("%s already exists%s.", state_.save_path,
                shipped ? " and is a shipped scenario" : "");
    ImGui::Text("Overwrite it?");
    if (ImGui::Button("Overwrite")) {
      confirm_overwrite_ = false;
      CmdSave(state_.save_path, true);
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      confirm_overwrite_ = false;
      SetStatus("not saved");
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}



void AppUi::DrawViewSection() {
  if (ImGui::Button("Fit all (f)")) {
    state_.fit_now = true;
    state_.follow = -1;
  }
  ImGui::SameLine();
  ImGui::Checkbox("auto-fit", &state_.auto_fit);
  ImGui::SameLine();
  ImGui::Checkbox("whole run", &state_.whole_run);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "auto-fit keeps everything seen since the start in view\n(off: follows the robots)");
  const auto& robots = session_->exp().world().robots();
  std::string preview = state_.follow >= 0 && state_.follow < static_cast<int>(robots.size())
                            ? robots[state_.follow]->name()
                            : "nobody";
  ImGui::SetNextItemWidth(140);
  if (ImGui::BeginCombo("follow", preview.c_str())) {
    if (ImGui::Selectable("nobody", state_.follow < 0)) state_.follow = -1;
    for (std::size_t i = 0; i < robots.size(); ++i)
      if (ImGui::Selectable(robots[i]->name().c_str(), state_.follow == static_cast<int>(i))) {
        state_.follow = static_cast<int>(i);
        state_.auto_fit = false;
      }
    ImGui::EndCombo();
  }
  float zoom = static_cast<float>(state_.view.scale);
  ImGui::SetNextItemWidth(140);
  if (ImGui::SliderFloat("px per m", &zoom, 2.0f, 2000.0f, "%.0f", ImGuiSliderFlags_Logarithmic)) {
    state_.view.scale = std::max(0.5f, zoom);
    state_.auto_fit = false;
  }
  ImGui::Checkbox("grid", &state_.grid);
  ImGui::SameLine();
  ImGui::Checkbox("coordinates", &state_.coordinates);
  ImGui::SetNextItemWidth(140);
  if (ImGui::BeginCombo("theme", GetTheme(state_.theme).name)) {
    for (ThemeId id : {ThemeId::kLight, ThemeId::kDark, ThemeId::kPrint, ThemeId::kHighContrast})
      if (ImGui::Selectable(GetTheme(id).name, id == state_.theme)) {
        state_.theme = id;
        ApplyImGuiTheme(GetTheme(id));
      }
    ImGui::EndCombo();
  }
  if (ImGui::Button("Screenshot (s)")) state_.screenshot_requested = true;
  ImGui::TextDisabled("wheel: zoom, right-drag: pan,\nleft-drag a robot or obstacle while paused");
  ImGui::Separator();
  DrawOverlayToggles();
}

void AppUi::DrawMessagesSection() {
  const auto& rejected = session_->rejected();
  const auto& events = session_->exp().events().list();
  char title[64];
  std::snprintf(title, sizeof(title), "Messages (%zu rejected, %zu events)###messages",
                rejected.size(), events.size());
  if (!state_.status.empty()) {
    if (state_.status_is_error) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.75f, 0.1f, 0.1f, 1));
    LongTextWrapped("status", state_.status, 600);  // any length (app/render/long_text.hpp)
    if (state_.status_is_error) ImGui::PopStyleColor();
  }
  if (!ImGui::CollapsingHeader(title, rejected.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen))
    return;
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.75f, 0.1f, 0.1f, 1));
  for (auto it = rejected.rbegin(); it != rejected.rend() && it - rejected.rbegin() < 8; ++it)
    ImGui::TextWrapped("%s", Shorten(*it, 600).c_str());
  ImGui::PopStyleColor();
  const std::size_t first = events.size() > 12 ? events.size() - 12 : 0;
  for (std::size_t i = events.size(); i-- > first;)
    ImGui::TextWrapped("%.2f s %s %s: %s", events[i].time, events[i].kind.c_str(),
                       Shorten(events[i].robots, 200).c_str(), Shorten(events[i].message, 400).c_str());
}

}  // namespace formsim::app
