#include "app/gui/scenario_panel.hpp"

#include "app/gui/fitted_field.hpp"

#include <imgui.h>

#include <filesystem>
#include <memory>

#include "app/gui/command_row_makers.hpp"
#include "app/gui/history_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/render/long_text.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/session/session.hpp"

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace fs = std::filesystem;

namespace formsim::app {
namespace {

// The shipped scenarios by name (load).
std::vector<std::string> ShippedNames(const AppUi&) {
  std::vector<std::string> out;
  for (const std::string& f : sim::ShippedScenarios()) out.push_back(fs::path(f).stem().string());
  return out;
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

ScenarioPanel::ScenarioPanel(const PanelContext& ctx) : ctx_(ctx), shipped_(ShippedAndLessons()) {}

void ScenarioPanel::SyncScenario() {
  const std::string current = ctx_.session().file();
  // The loaded file's entry, or none (-1) for a file of the user's.
  shipped_index_ = -1;
  for (std::size_t i = 0; i < shipped_.size(); ++i)
    if (fs::path(shipped_[i]).filename() == fs::path(current).filename())
      shipped_index_ = static_cast<int>(i);
  CopyString(open_path_, sizeof open_path_, current);
  CopyString(save_path_, sizeof save_path_, fs::path(current).stem().string() + "_tuned.yaml");
}

std::string ScenarioPanel::CmdReload() {
  // The run replaced keeps its history row (PanelContext::replace_run).
  const std::string err = ctx_.replace_run("reloaded", [&] { return ctx_.session().Reload(); });
  if (!err.empty()) return ctx_.Refuse(err);
  ctx_.scenario_changed();
  ctx_.SetStatus("reloaded " + ctx_.session().file());
  return "";
}

std::string ScenarioPanel::CmdLoad(const std::string& name_or_path) {
  std::string file;
  try {
    file = sim::ResolveScenario(name_or_path);
  } catch (const std::exception& e) {
    return ctx_.Refuse(std::string("cannot load: ") + e.what());
  }
  return CmdOpen(file);
}

std::string ScenarioPanel::CmdOpen(const std::string& path) {
  // Copy first: `path` may refer to state that the new session replaces.
  const std::string file = path;
  try {
    ctx_.adopt(std::make_unique<sim::Session>(file, std::vector<sim::Override>{}), "loaded " + file);
  } catch (const std::exception& e) {
    return ctx_.Refuse(std::string("cannot load, the current scenario stays: ") + e.what());
  }
  return "";
}

std::string ScenarioPanel::CmdSave(const std::string& path, bool overwrite) {
  if (path.empty()) {
    return ctx_.Refuse("save: give a file name");
  }
  try {
    std::string note;
    if (ctx_.session().Save(path, overwrite, &note) == sim::Session::SaveResult::kNeedsConfirmation) {
      confirm_overwrite_ = true;
      ctx_.SetStatus(path + " exists: confirm to overwrite");
      return "";
    }
    std::string also;
    if (!ctx_.Find<HistoryPanel>()->history().empty()) {
      // The history goes beside the scenario and comes back when it is opened.
      const std::string hist = sim::RunHistory::PathFor(path);
      try {
        ctx_.Find<HistoryPanel>()->history().Save(hist);
        also = ", history in " + hist;
      } catch (const std::exception& e) {
        also = "; the history was not saved: " + std::string(e.what());
      }
    }
    ctx_.SetStatus("saved " + path + (note.empty() ? "" : " (" + note + ")") + also);
    ctx_.NoteFileWritten(path, "application/x-yaml");
  } catch (const std::exception& e) {
    return ctx_.Refuse(std::string("save failed: ") + e.what());
  }
  return "";
}

void ScenarioPanel::Draw(const Fonts&) {
  const sim::ExperimentSetup& setup = ctx_.session().exp().setup();
  LongTextWrapped("name", setup.name, 300);  // texts of any length (app/render/long_text.hpp)
  if (!setup.description.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    LongTextWrapped("description", setup.description);
    ImGui::PopStyleColor();
  }
  if (!shipped_.empty()) {
    const std::string preview =
        shipped_index_ >= 0 ? ListName(shipped_[shipped_index_]) : std::string("(a file of yours)");
    ImGui::SetNextItemWidth(WidthBeside("Load"));
    if (FittedCombo("##shipped", preview)) {
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
  ImGui::SetNextItemWidth(WidthBeside("Open"));
  FittedInputText("##open", open_path_, sizeof open_path_);
  ImGui::SameLine();
  if (ImGui::Button("Open")) CmdOpen(open_path_);
  if (ImGui::Button("Reload file")) CmdReload();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Reload from disk, dropping the tuned values");

  ImGui::SetNextItemWidth(WidthBeside("Save"));
  FittedInputText("##save", save_path_, sizeof save_path_);
  ImGui::SameLine();
  if (ImGui::Button("Save")) CmdSave(save_path_, false);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Write the scenario with the tuned values: the file's own text, comments\n"
                      "and layout, with only the changed values rewritten");
  if (confirm_overwrite_) ImGui::OpenPopup("Overwrite?");
  if (ImGui::BeginPopupModal("Overwrite?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    const bool shipped = sim::Session::IsShipped(save_path_);
    ImGui::Text("%s already exists%s.", save_path_,
                shipped ? " and is a shipped scenario" : "");
    ImGui::Text("Overwrite it?");
    if (ImGui::Button("Overwrite")) {
      confirm_overwrite_ = false;
      CmdSave(save_path_, true);
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      confirm_overwrite_ = false;
      ctx_.SetStatus("not saved");
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

std::vector<Command> ScenarioPanel::Rows() {
  using namespace rows;
  using Src = CommandSource;
  auto panel = [](AppUi& ui) { return ui.Find<ScenarioPanel>(); };
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "open",
       .args = {Initial(Text("PATH", "a scenario file's path"),
                        [](const AppUi& ui) { return std::string(ui.Find<ScenarioPanel>()->open_path_); })},
       .menu = "File/Open…",
       .help = "Open a scenario file (the current run stays when it cannot be read)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) { return panel(ui)->CmdOpen(a.Text(0)); }});
  row({.name = "load",
       .args = {Offer(Text("SCENARIO", "a shipped scenario's name, or a path"), ShippedNames)},
       .menu = "File/Load shipped",
       .help = "Load a shipped scenario by name (or a file by path)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) { return panel(ui)->CmdLoad(a.Text(0)); }});
  row({.name = "reload",
       .menu = "File/Reload from disk",
       .help = "Read the scenario file again, dropping the tuned values",
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdReload(); }});
  row({.name = "save",
       .args = {Optional(Text("PATH", "a file to write"))},
       .menu = "File/Save",
       .help =
           "Save the tuned scenario (to PATH, else to the Save field's file); a script overwrites",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src s) {
         const std::string path = a.Has(0) ? a.Text(0) : std::string(panel(ui)->save_path_);
         return panel(ui)->CmdSave(path, s == Src::kScript);
       }});
  row({.name = "save-as",
       .args = {Initial(Text("PATH", "a file to write"),
                        [](const AppUi& ui) { return std::string(ui.Find<ScenarioPanel>()->save_path_); })},
       .menu = "File/Save as…",
       .help = "Save the tuned scenario to PATH (asks before overwriting; a script overwrites)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src s) {
         return panel(ui)->CmdSave(a.Text(0), s == Src::kScript);
       }});
  return t;
}

}  // namespace formsim::app
