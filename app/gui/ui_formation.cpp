/// \file The formation editor of the interface: add a follower (pick its leaders in the world
/// view, then where it goes), remove one, re-attach one to other leaders, switch its law, drag
/// desired slots, and named shapes in one click. Every change is a command of the session
/// (Session::Restructure, or live edits for a slot), checked by the scenario loader like a file:
/// a refused change is shown with its reason and the run goes on as it was.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/render/imgui_canvas.hpp"
#include "app/gui/ui.hpp"
#include "control/formation/formation_shapes.hpp"
#include "sim/core/number_format.hpp"
#include "sim/formation/formation_editing.hpp"

namespace formsim::app {
namespace {

using EditMode = UiState::EditMode;
using control::formation::FormationLaw;
namespace sf = sim::formation;

// The editor's law choice (UiState::edit_law: 0 l-φ, 1 l-l).
FormationLaw LawOf(int edit_law) {
  return edit_law == 0 ? FormationLaw::kLPhi : FormationLaw::kLL;
}

std::string Joined(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : ",") + s;
  return out;
}

// A clicked point to 0.1 mm: the change's text stays readable in the session record.
double Rounded(double v) {
  return std::round(v * 1e4) / 1e4 + 0.0;
}
std::string Coord(double v) {
  return sim::FormatDouble(Rounded(v));
}

// Leaders a law needs.
std::size_t Needed(int edit_law) {
  return control::formation::LeadersOfLaw(LawOf(edit_law));
}

const char* ModeHint(EditMode m) {
  switch (m) {
    case EditMode::kAdd:
      return "click the leader(s), then where the new follower goes";
    case EditMode::kRemove:
      return "click the robot to remove";
    case EditMode::kAttach:
      return "click the follower, then its new leader(s)";
    case EditMode::kSwitchLaw:
      return "click a follower: l-l becomes l-φ to its first leader; l-φ becomes l-l (then click the second leader)";
    case EditMode::kSlots:
      return "drag a follower: its desired slot (control point) follows the mouse";
    case EditMode::kOff:
      break;
  }
  return "";
}

}  // namespace

std::string AppUi::CmdFormation(const std::string& command) {
  return RunRestructure(command, [&] { return sf::Restructure(*session_, command, "GUI edit"); });
}

std::string AppUi::CmdFormationChange(const sf::StructureChange& change) {
  return RunRestructure(sf::StructureChangeText(change),
                        [&] { return sf::Restructure(*session_, change, "GUI edit"); });
}

std::string AppUi::RunRestructure(const std::string& command,
                                  const std::function<std::string()>& restructure) {
  CmdLive();
  auto row = PendingRow("restructured");
  const std::string err = restructure();
  state_.edit_picks.clear();  // a refused change starts its picks again
  if (!err.empty()) {
    SetStatus("formation " + command + " refused: " + err, true);
    return err;
  }
  if (row) history_.Add(std::move(*row));
  state_.step_budget = 0;
  state_.edit_picks.clear();
  SetStatus("formation " + command + ": done, the run goes on from here");
  return "";
}

std::string AppUi::CmdSlot(const std::string& robot, double x, double y, bool continues_drag) {
  std::vector<std::pair<std::string, std::string>> edits;
  try {
    const sf::FormationEditing* editing = sf::EditingOf(session_->exp());
    if (editing == nullptr)
      throw std::runtime_error("this kind of scenario has no desired slots to drag");
    edits = editing->SlotEdits(robot, {x, y});
  } catch (const std::exception& e) {
    SetStatus(std::string("slot: ") + e.what(), true);
    return e.what();
  }
  // Each edit is checked with the whole scenario; two distances that only fit together (an l-l
  // triangle) are tried in the other order when the first alone is refused.
  std::string err = session_->Edit(edits[0].first, edits[0].second, "slot drag", continues_drag);
  if (!err.empty() && edits.size() > 1) {
    if (session_->Edit(edits[1].first, edits[1].second, "slot drag", continues_drag).empty()) {
      err = session_->Edit(edits[0].first, edits[0].second, "slot drag", continues_drag);
      edits.pop_back();
    }
  }
  for (std::size_t k = 1; k < edits.size() && err.empty(); ++k)
    err = session_->Edit(edits[k].first, edits[k].second, "slot drag", continues_drag);
  if (!err.empty()) {
    SetStatus("slot of " + robot + " refused: " + err, true);
    return err;
  }
  SetStatus("slot of " + robot + " at (" + Coord(x) + ", " + Coord(y) + ")");
  return "";
}

std::string AppUi::CmdEditor(const std::string& mode) {
  std::string m = mode, law;
  if (const auto sp = mode.find(' '); sp != std::string::npos) {
    m = mode.substr(0, sp);
    law = mode.substr(mode.find_first_not_of(' ', sp));
  }
  auto set_law = [&]() -> std::string {
    if (law.empty()) return "";
    FormationLaw l;
    if (!control::formation::ParseLaw(law, &l))
      return "editor " + m + ": law must be " + control::formation::LawName(FormationLaw::kLPhi) +
             " or " + control::formation::LawName(FormationLaw::kLL) + ", got '" + law + "'";
    state_.edit_law = l == FormationLaw::kLPhi ? 0 : 1;
    return "";
  };
  EditMode next;
  if (m == "off") next = EditMode::kOff;
  else if (m == "add") next = EditMode::kAdd;
  else if (m == "remove") next = EditMode::kRemove;
  else if (m == "attach") next = EditMode::kAttach;
  else if (m == "law") next = EditMode::kSwitchLaw;
  else if (m == "slots") next = EditMode::kSlots;
  else {
    const std::string why = "editor: expects off, add [l_phi|l_l], remove, attach [l_phi|l_l], law or slots, got '" + mode + "'";
    SetStatus(why, true);
    return why;
  }
  if (next != EditMode::kOff && sf::EditingOf(session_->exp()) == nullptr) {
    const std::string why = "editor: this scenario has no formation to edit";
    SetStatus(why, true);
    return why;
  }
  if (std::string err = set_law(); !err.empty()) {
    SetStatus(err, true);
    return err;
  }
  state_.edit_mode = next;
  state_.edit_picks.clear();
  state_.slot_drag.clear();
  SetStatus(next == EditMode::kOff ? "editor off" : ModeHint(next));
  return "";
}

std::string AppUi::RobotAt(Vec2 p, const View& view) const {
  std::string name;
  double best = 1e300;
  for (const auto& r : session_->exp().world().robots()) {
    const double reach = std::max(r->def().half_length, r->def().radius) + 8.0 / view.scale;
    const double d = (r->pose().p() - p).Norm();
    if (d < reach && d < best) best = d, name = r->name();
  }
  return name;
}

std::string AppUi::EditorClick(Vec2 p) {
  const std::string hit = RobotAt(p, state_.view);
  auto& picks = state_.edit_picks;
  const FormationLaw law = LawOf(state_.edit_law);
  const sf::FormationEditing* editing = sf::EditingOf(session_->exp());
  auto leaders_of = [&](const std::string& robot) {
    return editing != nullptr ? editing->LeadersOf(robot) : std::vector<std::string>{};
  };
  auto picked = [&](const std::string& what) {
    SetStatus(what + ": " + Joined(picks));
    return std::string();
  };
  switch (state_.edit_mode) {
    case EditMode::kOff:
      return "editor: off (choose what a click does first)";
    case EditMode::kRemove:
      if (hit.empty()) return picked("no robot there; click the robot to remove");
      return CmdFormationChange({sf::RemoveRobot{hit}});
    case EditMode::kAdd:
      if (!hit.empty()) {
        if (std::find(picks.begin(), picks.end(), hit) == picks.end()) {
          if (picks.size() == Needed(state_.edit_law)) picks.pop_back();
          picks.push_back(hit);
        }
        return picked(picks.size() == Needed(state_.edit_law) ? "leaders (now click where the follower goes)"
                                                             : "leaders so far");
      }
      if (picks.size() != Needed(state_.edit_law)) {
        const std::string why = "add: pick " + std::to_string(Needed(state_.edit_law)) +
                                " leader(s) for " + control::formation::LawName(law) +
                                " first (click them)";
        SetStatus(why, true);
        return why;
      }
      return CmdFormationChange({sf::AddFollower{law, picks, Rounded(p.x), Rounded(p.y), ""}});
    case EditMode::kAttach:
      if (hit.empty()) return picked("no robot there; follower, then leader(s)");
      if (std::find(picks.begin(), picks.end(), hit) == picks.end()) picks.push_back(hit);
      if (picks.size() < 1 + Needed(state_.edit_law)) return picked("follower, leaders");
      return CmdFormationChange(
          {sf::AttachFollower{picks[0], law, {picks.begin() + 1, picks.end()}}});
    case EditMode::kSwitchLaw: {
      if (hit.empty()) return picked("no robot there; click a follower");
      if (picks.empty()) {
        const std::vector<std::string> leaders = leaders_of(hit);
        if (leaders.empty()) {
          const std::string why = hit + " is a root leader: it has no law to switch";
          SetStatus(why, true);
          return why;
        }
        if (leaders.size() == 2)
          return CmdFormationChange({sf::AttachFollower{hit, FormationLaw::kLPhi, {leaders[0]}}});
        picks = {hit, leaders[0]};
        return picked("l-φ -> l-l: now click the second leader for");
      }
      if (hit == picks[0] || hit == picks[1]) return picked("click another robot as second leader");
      return CmdFormationChange({sf::AttachFollower{picks[0], FormationLaw::kLL, {picks[1], hit}}});
    }
    case EditMode::kSlots:
      if (!hit.empty() && state_.slot_drag.empty()) {
        if (leaders_of(hit).empty()) {
          const std::string why = hit + " is a root leader: it has no desired slot";
          SetStatus(why, true);
          return why;
        }
        state_.slot_drag = hit;
        SetStatus("slot of " + hit + ": click or drag where it should be");
        return "";
      }
      if (state_.slot_drag.empty()) return picked("no follower there");
      return CmdSlot(state_.slot_drag, p.x, p.y);
  }
  return "";
}

bool AppUi::EditorMouse(const View& view) {
  if (state_.edit_mode == EditMode::kOff) return false;
  ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsItemHovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    const Vec2 p = view.ToWorld(io.MousePos);
    if (state_.edit_mode == EditMode::kSlots) {
      state_.slot_drag.clear();
      EditorClick(p);
      state_.gesture_key.clear();
    } else {
      EditorClick(p);
    }
  }
  if (state_.edit_mode == EditMode::kSlots && !state_.slot_drag.empty() &&
      ImGui::IsMouseDown(ImGuiMouseButton_Left) && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 2.0f)) {
    const Vec2 p = view.ToWorld(io.MousePos);
    // The drag's edits make one undo step.
    const bool continues = state_.gesture_key == "slot:" + state_.slot_drag;
    CmdSlot(state_.slot_drag, p.x, p.y, continues);
    state_.gesture_key = "slot:" + state_.slot_drag;
  }
  if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && state_.edit_mode == EditMode::kSlots) {
    state_.slot_drag.clear();
    state_.gesture_key.clear();
  }
  return true;
}

void AppUi::DrawFormationSection() {
  const sim::Experiment& exp = session_->exp();
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("Click in the world view to build the formation; every change is checked "
                      "like a scenario file (cycle, missing leader, impossible triangle).");
  ImGui::PopTextWrapPos();
  ImGui::TextUnformatted("law");
  ImGui::SameLine();
  ImGui::RadioButton("l-φ", &state_.edit_law, 0);
  ImGui::SameLine();
  ImGui::RadioButton("l-l", &state_.edit_law, 1);
  auto mode_button = [&](const char* label, EditMode m, const char* command) {
    const bool on = state_.edit_mode == m;
    if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyle().Colors[ImGuiCol_ButtonActive]);
    if (ImGui::Button(label)) CmdEditor(on ? "off" : command);
    if (on) ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", ModeHint(m));
  };
  mode_button("Add follower", EditMode::kAdd, "add");
  ImGui::SameLine();
  mode_button("Remove", EditMode::kRemove, "remove");
  ImGui::SameLine();
  mode_button("Re-attach", EditMode::kAttach, "attach");
  mode_button("Switch law", EditMode::kSwitchLaw, "law");
  ImGui::SameLine();
  mode_button("Drag slots", EditMode::kSlots, "slots");
  ImGui::SameLine();
  ImGui::BeginDisabled(state_.edit_mode == EditMode::kOff);
  if (ImGui::Button("Done")) CmdEditor("off");
  ImGui::EndDisabled();
  if (state_.edit_mode != EditMode::kOff) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(0.15f, 0.45f, 0.9f, 1), "%s%s%s", ModeHint(state_.edit_mode),
                       state_.edit_picks.empty() ? "" : "; picked: ",
                       Joined(state_.edit_picks).c_str());
    ImGui::PopTextWrapPos();
  }
  // A refused change says why right here (the status line may be scrolled out of view).
  if (state_.status_is_error && !state_.status.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(0.8f, 0.1f, 0.1f, 1), "%s", state_.status.c_str());
    ImGui::PopTextWrapPos();
  }
  // Named shapes: the whole graph and every slot in one click.
  const auto& shapes = control::formation::ShapeNames();
  state_.shape_index = std::clamp(state_.shape_index, 0, static_cast<int>(shapes.size()) - 1);
  ImGui::SetNextItemWidth(120);
  if (ImGui::BeginCombo("##shape", shapes[state_.shape_index].c_str())) {
    for (std::size_t i = 0; i < shapes.size(); ++i)
      if (ImGui::Selectable(shapes[i].c_str(), static_cast<int>(i) == state_.shape_index))
        state_.shape_index = static_cast<int>(i);
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputFloat("m##spacing", &state_.shape_spacing, 0, 0, "%.2f");
  ImGui::SameLine();
  if (ImGui::Button("Apply shape"))
    CmdFormationChange(
        {sf::ApplyShape{static_cast<control::formation::ShapeKind>(state_.shape_index),
                        Rounded(state_.shape_spacing)}});
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Every robot after the root leader is placed on its slot of the shape,\n"
                      "with l-l links wherever a well-shaped triangle exists (else l-φ)");
  ImGui::TextDisabled("%zu robots; Ctrl+Z undoes a change", exp.world().robots().size());
}

}  // namespace formsim::app
