#include "app/gui/parameters_panel.hpp"
#include "app/gui/formation_editor_panel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "app/gui/command_row_makers.hpp"
#include "app/gui/run_panel.hpp"
#include "app/gui/timeline_panel.hpp"
#include "app/gui/ui.hpp"
#include "app/render/imgui_canvas.hpp"
#include "control/formation/formation_graph.hpp"
#include "control/formation/formation_shapes.hpp"
#include "sim/core/number_format.hpp"
#include "sim/formation/formation_editing.hpp"

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace formsim::app {
namespace {

using EditMode = FormationEditorPanel::EditMode;
using control::formation::FormationLaw;
namespace sf = sim::formation;

// The editor's law choice (0 l-φ, 1 l-l).
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

std::string FormationEditorPanel::CmdFormation(const std::string& command) {
  return RunRestructure(command,
                        [&] { return sf::Restructure(ctx_.session(), command, "GUI edit"); });
}

std::string FormationEditorPanel::CmdFormationChange(const sf::StructureChange& change) {
  return RunRestructure(sf::StructureChangeText(change),
                        [&] { return sf::Restructure(ctx_.session(), change, "GUI edit"); });
}

std::string FormationEditorPanel::RunRestructure(const std::string& command,
                                                 const std::function<std::string()>& restructure) {
  ctx_.Find<TimelinePanel>()->CmdLive();
  const std::string err = ctx_.replace_run("restructured", restructure);
  picks_.clear();  // a refused change starts its picks again
  if (!err.empty()) {
    ctx_.SetStatus("formation " + command + " refused: " + err, true);
    return err;
  }
  ctx_.Find<RunPanel>()->ForgetOwedTime();
  ctx_.SetStatus("formation " + command + ": done, the run goes on from here");
  return "";
}

std::string FormationEditorPanel::CmdSlot(const std::string& robot, double x, double y, bool continues_drag) {
  std::vector<std::pair<std::string, std::string>> edits;
  try {
    const sf::FormationEditing* editing = sf::EditingOf(ctx_.session().exp());
    if (editing == nullptr)
      throw std::runtime_error("this kind of scenario has no desired slots to drag");
    edits = editing->SlotEdits(robot, {x, y});
  } catch (const std::exception& e) {
    ctx_.SetStatus(std::string("slot: ") + e.what(), true);
    return e.what();
  }
  // Each edit is checked with the whole scenario; two distances that only fit together (an l-l
  // triangle) are tried in the other order when the first alone is refused.
  std::string err =
      ctx_.session().Edit(edits[0].first, edits[0].second, "slot drag", continues_drag);
  if (!err.empty() && edits.size() > 1) {
    if (ctx_.session().Edit(edits[1].first, edits[1].second, "slot drag", continues_drag).empty()) {
      err = ctx_.session().Edit(edits[0].first, edits[0].second, "slot drag", continues_drag);
      edits.pop_back();
    }
  }
  for (std::size_t k = 1; k < edits.size() && err.empty(); ++k)
    err = ctx_.session().Edit(edits[k].first, edits[k].second, "slot drag", continues_drag);
  if (!err.empty()) {
    ctx_.SetStatus("slot of " + robot + " refused: " + err, true);
    return err;
  }
  ctx_.SetStatus("slot of " + robot + " at (" + Coord(x) + ", " + Coord(y) + ")");
  return "";
}

std::string FormationEditorPanel::CmdEditor(const std::string& mode) {
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
    law_ = l == FormationLaw::kLPhi ? 0 : 1;
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
    ctx_.SetStatus(why, true);
    return why;
  }
  if (next != EditMode::kOff && sf::EditingOf(ctx_.session().exp()) == nullptr) {
    const std::string why = "editor: this scenario has no formation to edit";
    ctx_.SetStatus(why, true);
    return why;
  }
  if (std::string err = set_law(); !err.empty()) {
    ctx_.SetStatus(err, true);
    return err;
  }
  mode_ = next;
  picks_.clear();
  slot_drag_.clear();
  ctx_.SetStatus(next == EditMode::kOff ? "editor off" : ModeHint(next));
  return "";
}

std::string FormationEditorPanel::RobotAt(Vec2 p, const View& view) const {
  std::string name;
  double best = 1e300;
  for (const auto& r : ctx_.session().exp().world().robots()) {
    const double reach = std::max(r->def().half_length, r->def().radius) + 8.0 / view.scale;
    const double d = (r->pose().p() - p).Norm();
    if (d < reach && d < best) best = d, name = r->name();
  }
  return name;
}

std::string FormationEditorPanel::EditorClick(Vec2 p) {
  const std::string hit = RobotAt(p, ctx_.state->view);
  auto& picks = picks_;
  const FormationLaw law = LawOf(law_);
  const sf::FormationEditing* editing = sf::EditingOf(ctx_.session().exp());
  auto leaders_of = [&](const std::string& robot) {
    return editing != nullptr ? editing->LeadersOf(robot) : std::vector<std::string>{};
  };
  auto picked = [&](const std::string& what) {
    ctx_.SetStatus(what + ": " + Joined(picks));
    return std::string();
  };
  switch (mode_) {
    case EditMode::kOff:
      return "editor: off (choose what a click does first)";
    case EditMode::kRemove:
      if (hit.empty()) return picked("no robot there; click the robot to remove");
      return CmdFormationChange({sf::RemoveRobot{hit}});
    case EditMode::kAdd:
      if (!hit.empty()) {
        if (std::find(picks.begin(), picks.end(), hit) == picks.end()) {
          if (picks.size() == Needed(law_)) picks.pop_back();
          picks.push_back(hit);
        }
        return picked(picks.size() == Needed(law_) ? "leaders (now click where the follower goes)"
                                                             : "leaders so far");
      }
      if (picks.size() != Needed(law_)) {
        const std::string why = "add: pick " + std::to_string(Needed(law_)) +
                                " leader(s) for " + control::formation::LawName(law) +
                                " first (click them)";
        ctx_.SetStatus(why, true);
        return why;
      }
      return CmdFormationChange({sf::AddFollower{law, picks, Rounded(p.x), Rounded(p.y), ""}});
    case EditMode::kAttach:
      if (hit.empty()) return picked("no robot there; follower, then leader(s)");
      if (std::find(picks.begin(), picks.end(), hit) == picks.end()) picks.push_back(hit);
      if (picks.size() < 1 + Needed(law_)) return picked("follower, leaders");
      return CmdFormationChange(
          {sf::AttachFollower{picks[0], law, {picks.begin() + 1, picks.end()}}});
    case EditMode::kSwitchLaw: {
      if (hit.empty()) return picked("no robot there; click a follower");
      if (picks.empty()) {
        const std::vector<std::string> leaders = leaders_of(hit);
        if (leaders.empty()) {
          const std::string why = hit + " is a root leader: it has no law to switch";
          ctx_.SetStatus(why, true);
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
      if (!hit.empty() && slot_drag_.empty()) {
        if (leaders_of(hit).empty()) {
          const std::string why = hit + " is a root leader: it has no desired slot";
          ctx_.SetStatus(why, true);
          return why;
        }
        slot_drag_ = hit;
        ctx_.SetStatus("slot of " + hit + ": click or drag where it should be");
        return "";
      }
      if (slot_drag_.empty()) return picked("no follower there");
      return CmdSlot(slot_drag_, p.x, p.y);
  }
  return "";
}

bool FormationEditorPanel::WorldMouse(const View& view) {
  if (mode_ == EditMode::kOff) return false;
  ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsItemHovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    const Vec2 p = view.ToWorld(io.MousePos);
    if (mode_ == EditMode::kSlots) {
      slot_drag_.clear();
      EditorClick(p);
      ctx_.state->gesture_key.clear();
    } else {
      EditorClick(p);
    }
  }
  if (mode_ == EditMode::kSlots && !slot_drag_.empty() &&
      ImGui::IsMouseDown(ImGuiMouseButton_Left) && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 2.0f)) {
    const Vec2 p = view.ToWorld(io.MousePos);
    // The drag's edits make one undo step.
    const bool continues = ctx_.state->gesture_key == "slot:" + slot_drag_;
    CmdSlot(slot_drag_, p.x, p.y, continues);
    ctx_.state->gesture_key = "slot:" + slot_drag_;
  }
  if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && mode_ == EditMode::kSlots) {
    slot_drag_.clear();
    ctx_.state->gesture_key.clear();
  }
  return true;
}

void FormationEditorPanel::Draw(const Fonts&) {
  if (mode_ != EditMode::kOff) ImGui::SetNextItemOpen(true);
  if (!ImGui::CollapsingHeader("Formation")) return;
  const sim::Experiment& exp = ctx_.session().exp();
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("Click in the world view to build the formation; every change is checked "
                      "like a scenario file (cycle, missing leader, impossible triangle).");
  ImGui::PopTextWrapPos();
  ImGui::TextUnformatted("law");
  ImGui::SameLine();
  ImGui::RadioButton("l-φ", &law_, 0);
  ImGui::SameLine();
  ImGui::RadioButton("l-l", &law_, 1);
  auto mode_button = [&](const char* label, EditMode m, const char* command) {
    const bool on = mode_ == m;
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
  ImGui::BeginDisabled(mode_ == EditMode::kOff);
  if (ImGui::Button("Done")) CmdEditor("off");
  ImGui::EndDisabled();
  if (mode_ != EditMode::kOff) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(0.15f, 0.45f, 0.9f, 1), "%s%s%s", ModeHint(mode_),
                       picks_.empty() ? "" : "; picked: ",
                       Joined(picks_).c_str());
    ImGui::PopTextWrapPos();
  }
  // A refused change says why right here (the status line may be scrolled out of view).
  if (ctx_.state->status_is_error && !ctx_.state->status.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(0.8f, 0.1f, 0.1f, 1), "%s", ctx_.state->status.c_str());
    ImGui::PopTextWrapPos();
  }
  // Named shapes: the whole graph and every slot in one click.
  const auto& shapes = control::formation::ShapeNames();
  shape_index_ = std::clamp(shape_index_, 0, static_cast<int>(shapes.size()) - 1);
  ImGui::SetNextItemWidth(120);
  if (ImGui::BeginCombo("##shape", shapes[shape_index_].c_str())) {
    for (std::size_t i = 0; i < shapes.size(); ++i)
      if (ImGui::Selectable(shapes[i].c_str(), static_cast<int>(i) == shape_index_))
        shape_index_ = static_cast<int>(i);
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputFloat("m##spacing", &shape_spacing_, 0, 0, "%.2f");
  ImGui::SameLine();
  if (ImGui::Button("Apply shape"))
    CmdFormationChange(
        {sf::ApplyShape{static_cast<control::formation::ShapeKind>(shape_index_),
                        Rounded(shape_spacing_)}});
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Every robot after the root leader is placed on its slot of the shape,\n"
                      "with l-l links wherever a well-shaped triangle exists (else l-φ)");
  ImGui::TextDisabled(
      "%s",
      sim::Sprintf("%zu robots; Ctrl+Z undoes a change", exp.world().robots().size()).c_str());
}

void FormationEditorPanel::DrawOverWorld(const sim::Experiment& shown, const View& view) {
  for (const auto& r : shown.world().robots()) {
    const bool picked = std::find(picks_.begin(), picks_.end(), r->name()) != picks_.end() ||
                        r->name() == slot_drag_;
    if (!picked) continue;
    const ImVec2 c = view.ToScreen(r->pose().p());
    const float rad =
        static_cast<float>(std::max(r->def().half_length, r->def().radius) * view.scale) + 8;
    ImGui::GetWindowDrawList()->AddCircle(c, rad, ToImColor({0.15f, 0.45f, 0.9f, 1}), 32, 3.0f);
  }
}

namespace {

using Src = CommandSource;

std::string NeedsFormation(const AppUi& ui) {
  return sf::EditingOf(ui.session().exp()) != nullptr
             ? ""
             : "only for a formation scenario (this one has no formation graph to edit)";
}

// Structural changes: a formation scenario whose structure can change.
std::string NeedsRestructurable(const AppUi& ui) {
  const auto* editing = sf::EditingOf(ui.session().exp());
  return editing == nullptr ? NeedsFormation(ui) : editing->StructureLocked();
}

std::string NeedsSwitching(const AppUi& ui) {
  for (const sim::ActionSpec& a : ui.session().exp().Actions())
    if (a.id == "switch-formation") return "";
  return "only for a scenario with formation switching (a `switching:` block)";
}

// The window's editor; a row's `disabled` has refused already when there is none.
FormationEditorPanel& Editor(AppUi& ui) {
  FormationEditorPanel* editor = ui.Find<FormationEditorPanel>();
  if (editor == nullptr) throw std::runtime_error(NeedsFormation(ui));
  return *editor;
}

}  // namespace

std::vector<Command> FormationEditorPanel::Rows() {
  using namespace rows;
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "editor",
       .args = {Choice("MODE", {"off", "add", "remove", "attach", "law", "slots"}),
                Optional(Choice("LAW", control::formation::FollowerLawNames()))},
       .menu = "Formation/Editor",
       .help = "What a left click in the world view does (add and attach take a law)",
       .disabled = NeedsFormation,
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return Editor(ui).CmdEditor(a.Has(1) ? a.Text(0) + " " + a.Text(1) : a.Text(0));
       }});
  row({.name = "formation",
       .args = {Text("CHANGE",
                     "add LAW LEADERS X Y [NAME], remove NAME, attach NAME LAW "
                     "LEADERS, or shape KIND [SPACING]")},
       .menu = "Formation/Change…",
       .help = "A structural change of the formation; the run goes on from here",
       .disabled = NeedsRestructurable,
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return Editor(ui).CmdFormation(a.Text(0));
       }});
  row({.name = "shape",
       .args = {Choice("KIND", control::formation::ShapeNames()),
                Optional(Real("SPACING", 0.05, 10, "m"))},
       .menu = "Formation/Shape",
       .help = "Re-attach every follower to make a shape (spacing in m)",
       .disabled = NeedsRestructurable,
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return Editor(ui).CmdFormation("shape " + a.Text(0) + (a.Has(1) ? " " + a.Text(1) : ""));
       }});
  row({.name = "slot",
       .args = {Offer(Text("ROBOT", "a follower's name", ArgType::kWord), RobotNames),
                Real("X", -1e4, 1e4, "m"), Real("Y", -1e4, 1e4, "m")},
       .menu = "Formation/Move a slot…",
       .help = "Put a follower's desired slot at world point (X, Y): it converges live",
       .disabled = NeedsFormation,
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return Editor(ui).CmdSlot(a.Text(0), a.Real(1), a.Real(2));
       }});
  row({.name = "click",
       .args = {Real("X", -1e4, 1e4, "m"), Real("Y", -1e4, 1e4, "m")},
       .menu = "Formation/Click at…",
       .help = "A left click in the world view at (X, Y), as the editor's mode takes it",
       .disabled = NeedsFormation,
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return Editor(ui).EditorClick({a.Real(0), a.Real(1)});
       }});
  row({.name = "switch-formation",
       .args = {Optional(Text("NAME", "a shape of the switching: block", ArgType::kWord))},
       .keys = {"n"},
       .menu = "Formation/Switch formation",
       .help = "Switch to the next formation shape, or the named one",
       .disabled = NeedsSwitching,
       .run = [](AppUi& ui, const CommandArgs& a, Src) {
         return ui.Find<ParametersPanel>()->CmdAction(a.Has(0) ? "switch-formation:" + a.Text(0)
                                      : std::string("switch-formation"));
       }});
  return t;
}

std::unique_ptr<Panel> MakeKindPanel(const PanelContext& ctx, const sim::Experiment& exp) {
  if (exp.As<sf::FormationEditing>() != nullptr)
    return std::make_unique<FormationEditorPanel>(ctx);
  return nullptr;
}

bool IsKindPanelFor(const Panel* panel, const sim::Experiment& exp) {
  if (exp.As<sf::FormationEditing>() != nullptr)
    return dynamic_cast<const FormationEditorPanel*>(panel) != nullptr;
  return panel == nullptr;
}

}  // namespace formsim::app
