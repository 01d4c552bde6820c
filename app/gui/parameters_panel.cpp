/// \file The Parameters panel (app/gui/parameters_panel.hpp), drawn: every tunable of the scenario's ParamTable (declared once,
/// where the scenario reader reads it), grouped by its group path ("Gains/R2" -> header
/// "Gains", node "R2"), plus the experiment's action buttons. Widgets never write the
/// experiment: they ask the session for an edit, which checks it against the whole scenario and
/// applies it between steps; a refused edit is marked at its widget with the reason. A value
/// that differs from the file is marked (its label in blue, a ↺ button that reverts it), one
/// waiting for a reset shows ↻; both live in a column of fixed width and every row has the
/// height of a widget, so nothing in the panel moves when an edit is made.
#include "app/gui/parameters_panel.hpp"

#include <imgui_internal.h>  // SetItemUsingMouseWheel

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "app/gui/command_row_makers.hpp"
#include "app/gui/fitted_field.hpp"
#include "app/gui/table_header.hpp"
#include "app/gui/tunable_label.hpp"
#include "app/render/label_markup.hpp"
#include "app/gui/ui.hpp"
#include "app/gui/value_entry.hpp"
#include "app/render/display_unit.hpp"
#include "app/render/long_text.hpp"
#include "sim/core/number_format.hpp"
#include "sim/session/session.hpp"

// Each row names only the fields it sets; the others keep their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace formsim::app {
namespace {

// Sub-groups of a header start open when there are at most this many.
constexpr std::size_t kOpenSubgroups = 8;

std::string Head(const std::string& group) {
  return group.substr(0, group.find('/'));
}
std::string Tail(const std::string& group) {
  const auto slash = group.find('/');
  return slash == std::string::npos ? "" : group.substr(slash + 1);
}

// What one row shows besides the value.
struct RowMarks {
  bool waiting = false;  ///< edited, waiting for a reset
  bool edited = false;   ///< differs from the file (with the command line's --set)
  std::string loaded;    ///< the file's value
  std::string refusal;   ///< why the last edit was refused
};

// What the user did in a row.
struct RowInput {
  std::string value;   ///< the new value as text when changed
  bool held = false;   ///< the widget is held (a slider being dragged)
  bool entry = false;  ///< Enter in the row's value entry
  bool revert = false;
};

// ImGui asserts on slider ranges beyond half the largest value of the type.
constexpr long long kIntSliderLimit = 1000000000LL;

// A slider over [lo, hi] that ImGui draws without asserting (and that is worth dragging).
bool SliderFits(double lo, double hi) {
  return std::isfinite(lo) && std::isfinite(hi) && lo < hi && std::abs(lo) <= sim::kSliderLimit &&
         std::abs(hi) <= sim::kSliderLimit;
}

// A text field holding `text`; returns what was typed when Enter is pressed ("" else). The
// session checks it like any edit.
std::string ValueField(const std::string& text) {
  char buf[128] = {};
  text.copy(buf, sizeof(buf) - 1);  // at most 127 bytes, as the field holds
  if (ImGui::InputText("##v", buf, sizeof(buf),
                       ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_CharsScientific))
    return buf;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("beyond any slider: type a value and press Enter");
  return "";
}

// A double-click or Ctrl+click on the widget just drawn: it opens the value entry.
bool OpensEntry() {
  return ImGui::IsItemHovered() &&
         (ImGui::IsMouseDoubleClicked(0) || (ImGui::IsMouseClicked(0) && ImGui::GetIO().KeyCtrl));
}

// The mouse wheel over the widget just drawn: its notches (0 none). The window under it does not
// scroll while a field is hovered.
int WheelNotches() {
  if (!ImGui::IsItemHovered()) return 0;
  ImGui::SetItemUsingMouseWheel();
  const float w = ImGui::GetIO().MouseWheel;
  if (w == 0.0f) return 0;
  const int n = static_cast<int>(std::lround(w));
  return n != 0 ? n : (w > 0 ? 1 : -1);
}

// The open value entry of a row: true when Enter was pressed (committed after the table is
// drawn); Esc or a click elsewhere closes it, nothing applied.
bool EntryRow(ValueEntry& entry) {
  switch (entry.Draw()) {
    case ValueEntry::Outcome::kNone:
      return false;
    case ValueEntry::Outcome::kCancel:
      entry.Close();
      return false;
    case ValueEntry::Outcome::kCommit:
      break;
  }
  return true;
}

// The row's label (the tunable's name with its unit, coloured when edited or refused) in the
// first column, with a tooltip that says everything about the tunable.
void ParamRowLabel(const sim::Param& p, const DisplayUnit& du, const RowMarks& marks) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::AlignTextToFramePadding();
  // The tunable's one name (app/gui/tunable_label.hpp: the palette shows the same), with its
  // subscripts.
  const std::string name = ShortenMarkup(TunableLabel(p), 200);
  const std::string unit = du.unit.empty() ? "" : " [" + du.unit + "]";
  const bool colour = !marks.refusal.empty() || marks.edited;
  if (colour)
    ImGui::PushStyleColor(ImGuiCol_Text, !marks.refusal.empty() ? ImVec4(0.75f, 0.1f, 0.1f, 1)
                                                                : ImVec4(0.15f, 0.45f, 0.9f, 1));
  // Too long for its column (a narrow panel, a large UI scale): shortened in its name, the unit
  // kept whole, as the tables' headers are; the tooltip has it in full.
  const std::string full = name + EscapeMarkup(unit);
  const std::string label = FitMarkupLabel(name, unit, ImGui::GetContentRegionAvail().x);
  MarkupTextItem(label);
  if (colour) ImGui::PopStyleColor();
  if (!ImGui::IsItemHovered()) return;
  std::string tip = label == full ? p.key : MarkupText(full) + "\n" + p.key;
  if (!p.tune.help.empty()) tip += "\n" + p.tune.help;
  if (p.kind == sim::Param::Kind::kDouble || p.kind == sim::Param::Kind::kInt)
    tip += "\nvalid: " + p.tune.ValidityText() +
           "\ndouble-click or Ctrl+click: type a value (Enter applies, Esc cancels); wheel: "
           "fine steps";
  tip += p.tune.live ? "\napplies on the next step" : "\napplies on reset";
  if (marks.edited) tip += "\nedited: the file has " + marks.loaded + " (↺ reverts)";
  if (!marks.refusal.empty()) tip += "\n\nlast edit refused: " + marks.refusal;
  SafeTooltip(tip);  // any length (app/render/long_text.hpp)
}

// A real tunable's widget: its open value entry, a slider in the unit shown, or a text field
// when no slider holds the value. Returns the new value as text ("" when unchanged).
std::string ParamDoubleWidget(const sim::Param& p, const std::string& shown, const DisplayUnit& du,
                              bool degrees, bool typing, ValueEntry& entry, RowInput& in) {
  double v = 0;
  if (!sim::ParseFiniteDouble(shown, &v)) v = p.value;
  // The declared slider range lies inside the validity; a file value outside the slider
  // widens it (still valid: the range between two valid values is valid).
  double lo = std::min(p.slider_min(), v), hi = std::max(p.slider_max(), v);
  const double k = du.scale;
  if (typing) {
    in.entry = EntryRow(entry);
    return "";
  }
  if (!SliderFits(lo * k, hi * k)) {
    // A value beyond any slider (an unbounded tunable edited to 1e308): a text field.
    const std::string typed = ValueField(sim::FormatDouble(v * k));
    double t = 0;
    if (typed.empty()) return "";
    return k != 1.0 && sim::ParseFiniteDouble(typed, &t) ? sim::FormatDouble(t / k) : typed;
  }
  // NoInput: ImGui's own Ctrl+click field would apply every keystroke; ours waits for Enter.
  ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_NoInput;
  if (p.tune.log_scale && lo > 0) flags |= ImGuiSliderFlags_Logarithmic;
  double shown_v = v * k, shown_lo = lo * k, shown_hi = hi * k;
  // The angle's unit on the slider too ("°/s", "deg²"); '%' never occurs in a unit.
  // A unit of letters is spaced from the number ("0.3283 deg²"); a degree sign is not ("60°/s").
  const std::string format =
      "%.4g" +
      (du.angle && k != 1.0 ? (du.unit.rfind("°", 0) == 0 ? "" : " ") + du.unit : std::string());
  const bool changed = ImGui::SliderScalar("##v", ImGuiDataType_Double, &shown_v, &shown_lo,
                                           &shown_hi, format.c_str(), flags);
  if (OpensEntry()) {
    entry.Open(p.key, ParamEntryText(p, shown, degrees));
    return "";
  }
  std::string out;
  // A press alone (the first click of a double-click) changes nothing: the value follows
  // the mouse once it drags.
  if (changed && ImGui::IsMouseDragging(0) && std::isfinite(shown_v))
    out = sim::FormatDouble(std::clamp(shown_v / k, lo, hi));
  if (const int n = WheelNotches(); n != 0 && out.empty()) out = FineStep(p, v, n, k);
  return out;
}

// An integer tunable's widget: its open value entry, a slider, or a text field when the range
// is too wide for ImGui's slider. Returns the new value as text ("" when unchanged).
std::string ParamIntWidget(const sim::Param& p, const std::string& shown, bool typing,
                           ValueEntry& entry, RowInput& in) {
  long long parsed = 0;
  const long long v = sim::ParseInteger(shown, -2147483647LL, 2147483647LL, &parsed)
                          ? parsed
                          : static_cast<long long>(p.value);
  const long long lo = std::min(static_cast<long long>(std::max(p.slider_min(), -1e9)), v);
  const long long hi = std::max(static_cast<long long>(std::min(p.slider_max(), 1e9)), v);
  // ImGui's integer slider asserts beyond half the int range: wider ones are a text field.
  if (typing) {
    in.entry = EntryRow(entry);
    return "";
  }
  if (lo < -kIntSliderLimit || hi > kIntSliderLimit || lo >= hi)
    return ValueField(std::to_string(v));
  int iv = static_cast<int>(v);
  const bool changed =
      ImGui::SliderInt("##v", &iv, static_cast<int>(lo), static_cast<int>(hi), "%d",
                       ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_NoInput);
  if (OpensEntry()) {
    entry.Open(p.key, shown);
    return "";
  }
  std::string out;
  if (changed && ImGui::IsMouseDragging(0)) out = std::to_string(std::clamp<long long>(iv, lo, hi));
  if (const int n = WheelNotches(); n != 0 && out.empty())
    out = FineStep(p, static_cast<double>(v), n, 1.0);
  return out;
}

// The widget of tunable `p` by its kind. Returns the new value as text ("" when unchanged).
std::string ParamWidget(const sim::Param& p, const std::string& shown, const DisplayUnit& du,
                        bool degrees, bool typing, ValueEntry& entry, RowInput& in) {
  switch (p.kind) {
    case sim::Param::Kind::kDouble:
      return ParamDoubleWidget(p, shown, du, degrees, typing, entry, in);
    case sim::Param::Kind::kInt:
      return ParamIntWidget(p, shown, typing, entry, in);
    case sim::Param::Kind::kBool: {
      bool v = shown == "true";
      if (ImGui::Checkbox("##v", &v)) return v ? "true" : "false";
      return "";
    }
    case sim::Param::Kind::kChoice: {
      std::string out;
      if (FittedCombo("##v", shown)) {
        for (const auto& c : p.choices)
          if (ImGui::Selectable(c.c_str(), c == shown) && c != shown) out = c;
        ImGui::EndCombo();
      }
      return out;
    }
  }
  return "";
}

// The marks column, always the same width whatever it shows: ↺ (revert) when edited, ↻ when
// waiting for a reset.
void ParamRowMarks(const RowMarks& marks, RowInput& in) {
  ImGui::TableSetColumnIndex(2);
  if (marks.edited) {
    if (ImGui::SmallButton("↺")) in.revert = true;
    if (ImGui::IsItemHovered())
      SafeTooltip("revert to the file's value " + marks.loaded);
  } else {
    ImGui::Dummy(ImVec2(ImGui::GetFontSize() + 4, 1));
  }
  if (marks.waiting) {
    ImGui::SameLine(0, 2);
    ImGui::TextColored(ImVec4(0.8f, 0.45f, 0.0f, 1.0f), "↻");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("changed: applies on reset (r)");
  }
}

// One row: label (with unit), widget, and the fixed-width marks column. `shown` is the value to
// show (the one waiting for a reset, if any). Angles are shown in the unit of the window's
// setting (app/render/display_unit.hpp); the value stored and edited stays in radians.
RowInput ParamRow(const sim::Param& p, const std::string& shown, const RowMarks& marks,
                  bool degrees, ValueEntry& entry) {
  const DisplayUnit du = p.kind == sim::Param::Kind::kDouble ? ShownUnit(p.tune.unit, degrees)
                                                             : DisplayUnit{1.0, p.tune.unit, false};
  RowInput in;
  ParamRowLabel(p, du, marks);
  ImGui::TableSetColumnIndex(1);
  ImGui::SetNextItemWidth(-1.0f);
  ImGui::PushID(p.key.c_str());
  const std::string& refusal = marks.refusal;
  if (!refusal.empty()) ImGui::PushStyleColor(ImGuiCol_FrameBg, ImVec4(0.95f, 0.75f, 0.75f, 1));
  const bool typing = entry.IsOpen(p.key);
  in.value = ParamWidget(p, shown, du, degrees, typing, entry, in);
  in.held = !typing && ImGui::IsItemActive();
  if (!refusal.empty()) ImGui::PopStyleColor();
  ParamRowMarks(marks, in);
  ImGui::PopID();
  return in;
}

// What the rows offer: the tunables, the scenario's actions.
std::vector<std::string> TunableKeys(const AppUi& ui) {
  std::vector<std::string> out;
  for (const sim::Param& p : ui.session().params().all()) out.push_back(p.key);
  return out;
}

std::vector<std::string> ActionIds(const AppUi& ui) {
  std::vector<std::string> out;
  for (const sim::ActionSpec& a : ui.session().exp().Actions()) out.push_back(a.id);
  return out;
}

std::string NeedsActions(const AppUi& ui) {
  return ActionIds(ui).empty() ? "this scenario offers no actions" : "";
}

}  // namespace

const ParametersPanel::Grouping& ParametersPanel::Groups(
    const sim::ParamTable& table, const std::vector<sim::ActionSpec>& actions) {
  Grouping& g = grouping_;
  // The same table (comparing a thousand robots' groups took 0.5 ms a frame) and the same
  // action groups in the same order.
  const std::vector<sim::Param>& params = table.all();
  bool same = g.params_revision == table.revision() && g.action_groups.size() == actions.size();
  for (std::size_t i = 0; same && i < actions.size(); ++i)
    same = g.action_groups[i] == actions[i].group;
  if (same) return g;
  g = Grouping();
  // One pass over the groups: a set of those seen and a map to each one's place.
  std::unordered_map<std::string, std::size_t> head_at;
  std::unordered_map<std::string, std::pair<std::size_t, std::size_t>> sub_at;
  auto place = [&](const std::string& group) -> Grouping::Sub& {
    const auto known = sub_at.find(group);
    if (known != sub_at.end()) return g.heads[known->second.first].subs[known->second.second];
    const std::string h = Head(group), t = Tail(group);
    const auto [it, fresh] = head_at.try_emplace(h, g.heads.size());
    if (fresh)
      g.heads.push_back(
          {h, (h.empty() ? std::string("Parameters") : Shorten(h, 120)) + "###grp_" + h, {}});
    Grouping::Head& head = g.heads[it->second];
    head.subs.push_back(
        {t, group, t.empty() ? "" : Shorten(t, 120) + "##" + group, "##tbl" + group, {}, {}});
    sub_at[group] = {it->second, head.subs.size() - 1};
    return head.subs.back();
  };
  g.params_revision = table.revision();
  for (std::size_t i = 0; i < params.size(); ++i) {
    place(params[i].tune.group).params.push_back(i);
  }
  for (std::size_t i = 0; i < actions.size(); ++i) {
    g.action_groups.push_back(actions[i].group);
    place(actions[i].group).actions.push_back(i);
  }
  return g;
}

void ParametersPanel::Draw(const Fonts&) {
  const auto& params = ctx_.session().params().all();
  const auto actions = ctx_.session().exp().Actions();
  const Grouping& groups = Groups(ctx_.session().params(), actions);
  struct Asked {
    std::string key, value;
    bool held;
  };
  bool committed = false;  // Enter in the value entry
  std::vector<Asked> edits;
  std::vector<std::string> reverts;
  std::vector<std::string> run_actions;
  const auto waiting = ctx_.session().waiting_for_reset();
  // The palette asked for a tunable: open the way to its field.
  const sim::Param* focus =
      focus_param_.empty() ? nullptr : ctx_.session().params().Find(focus_param_);
  for (const Grouping::Head& head : groups.heads) {
    if (focus != nullptr && Head(focus->tune.group) == head.head) ImGui::SetNextItemOpen(true);
    if (!ImGui::CollapsingHeader(head.header.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) continue;
    // Sub-groups start open unless there are many (one per robot of a swarm).
    const ImGuiTreeNodeFlags node_flags =
        head.subs.size() <= kOpenSubgroups ? ImGuiTreeNodeFlags_DefaultOpen : 0;
    // A closed sub-group's row well outside the panel's visible part is not submitted: a run of
    // them becomes one gap of their measured height (a thousand robots' closed rows took 0.4 ms
    // a frame as tree nodes). Two rows on either side are still submitted.
    const ImVec2 clip_min = ImGui::GetWindowDrawList()->GetClipRectMin();
    const ImVec2 clip_max = ImGui::GetWindowDrawList()->GetClipRectMax();
    if (closed_row_.font_size != ImGui::GetFontSize()) closed_row_ = {ImGui::GetFontSize(), 0.0f};
    const float step = closed_row_.step;
    float gap = 0.0f;  // the rows left out since the last one submitted
    auto close_gap = [&] {
      if (gap > 0.0f) ImGui::Dummy(ImVec2(0.0f, gap - ImGui::GetStyle().ItemSpacing.y));
      gap = 0.0f;
    };
    for (const Grouping::Sub& sub : head.subs) {
      bool open = true;
      if (!sub.tail.empty()) {
        const bool focused = focus != nullptr && focus->tune.group == sub.group;
        if (!focused && step > 0.0f) {
          const float y = ImGui::GetCursorScreenPos().y + gap;
          const bool far = y + 3 * step < clip_min.y || y - 2 * step > clip_max.y;
          // The node's ID as ImGui::GetID makes it, hashed once per ID seed.
          const ImGuiID seed = ImGui::GetCurrentWindow()->IDStack.back();
          if (sub.id_seed != seed || sub.id == 0) sub.id = ImHashStr(sub.label.c_str(), 0, seed);
          sub.id_seed = seed;
          if (far && !ImGui::TreeNodeBehaviorIsOpen(sub.id, node_flags)) {
            gap += step;
            continue;
          }
        }
        close_gap();
        if (focused) ImGui::SetNextItemOpen(true);
        const float y0 = ImGui::GetCursorPosY();
        open = ImGui::TreeNodeEx(sub.label.c_str(), node_flags);
        if (!open) closed_row_.step = ImGui::GetCursorPosY() - y0;
      }
      if (!open) continue;
      if (!sub.params.empty() &&
          ImGui::BeginTable(sub.table_id.c_str(), 3, ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("label", ImGuiTableColumnFlags_WidthStretch, 0.45f);
        ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch, 0.55f);
        ImGui::TableSetupColumn("marks", ImGuiTableColumnFlags_WidthFixed,
                                2 * ImGui::GetFontSize() + 12);
        for (const std::size_t i : sub.params) {
          const sim::Param& p = params[i];
          const auto w = waiting.find(p.key);
          RowMarks marks;
          marks.waiting = w != waiting.end();
          marks.edited = ctx_.session().IsEdited(p.key);
          marks.loaded = ctx_.session().LoadedValue(p.key);
          marks.refusal = ctx_.session().refusal(p.key);
          const std::string& shown = marks.waiting ? w->second : p.Text();
          if (p.key == focus_param_) {
            ImGui::SetScrollHereY(0.3f);
            // A number is typed into the value entry; a switch or a choice takes the keyboard.
            const bool number =
                p.kind == sim::Param::Kind::kDouble || p.kind == sim::Param::Kind::kInt;
            if (!number) ImGui::SetKeyboardFocusHere();
            else if (!value_entry_.IsOpen(p.key))
              value_entry_.Open(p.key, ParamEntryText(p, shown, ctx_.state->settings.degrees));
            focus_param_.clear();
          }
          const RowInput in = ParamRow(p, shown, marks, ctx_.state->settings.degrees, value_entry_);
          if (!in.value.empty()) edits.push_back({p.key, in.value, in.held});
          committed = committed || in.entry;
          if (in.revert) reverts.push_back(p.key);
        }
        ImGui::EndTable();
      }
      for (const std::size_t i : sub.actions) {
        const sim::ActionSpec& a = actions[i];
        if (ImGui::Button(a.label.c_str())) run_actions.push_back(a.id);
        if (!a.help.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", a.help.c_str());
      }
      if (!sub.tail.empty()) ImGui::TreePop();
    }
    close_gap();
  }
  // Asked for after the loop: an edit never changes the table while we iterate over it. The edits
  // of a slider held since its last edit continue that edit (one undo step).
  if (committed) CmdFieldKey(true);
  for (const Asked& e : edits) {
    CmdEdit(e.key, e.value, e.held && ctx_.state->gesture_key == e.key);
    if (e.held) ctx_.state->gesture_key = e.key;
  }
  for (const auto& key : reverts) CmdRevert(key);
  for (const auto& id : run_actions) CmdAction(id);
}

std::string ParametersPanel::CmdEdit(const std::string& key, const std::string& value, bool continues_drag) {
  const std::string err = ctx_.session().Edit(key, value, "GUI edit", continues_drag);
  if (!err.empty()) ctx_.SetStatus("edit " + key + "=" + value + " refused: " + err, true);
  return err;
}

std::string ParametersPanel::CmdAction(const std::string& id) {
  const std::string err = ctx_.session().Action(id);
  if (!err.empty()) ctx_.SetStatus(err, true);
  else ctx_.SetStatus("action " + id);
  return err;
}

std::string ParametersPanel::CmdUndo() {
  const std::string text = ctx_.session().UndoText();
  const std::string err = ctx_.session().Undo();
  ctx_.SetStatus(err.empty() ? "undo " + text : err, !err.empty() && ctx_.session().can_undo());
  return err;
}

std::string ParametersPanel::CmdRedo() {
  const std::string text = ctx_.session().RedoText();
  const std::string err = ctx_.session().Redo();
  ctx_.SetStatus(err.empty() ? "redo " + text : err, !err.empty() && ctx_.session().can_redo());
  return err;
}

std::string ParametersPanel::CmdRevert(const std::string& key) {
  const std::string loaded = ctx_.session().LoadedValue(key);
  if (loaded.empty()) {
    const std::string why = "revert: no tunable '" + key + "'";
    ctx_.SetStatus(why, true);
    return why;
  }
  const std::string err = ctx_.session().Edit(key, loaded, "revert");
  if (!err.empty())
    ctx_.SetStatus("revert " + key + " refused: " + err, true);
  else
    ctx_.SetStatus("reverted " + key + " to " + loaded);
  return err;
}

std::vector<Command> ParametersPanel::Rows() {
  using namespace rows;
  using Src = CommandSource;
  auto panel = [](AppUi& ui) { return ui.Find<ParametersPanel>(); };
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "edit",
       .args = {Offer(Text("KEY=VALUE", "a tunable's key, '=', and its new value"), TunableKeys)},
       .menu = "Run/Edit a value…",
       .help = "Change a tunable, checked as the loader would (live, or at the next reset)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) {
         const std::string& kv = a.Text(0);
         const auto eq = kv.find('=');
         if (eq == std::string::npos || eq == 0)
           return "edit: KEY=VALUE expects a tunable's key, '=', and its new value, got '" +
                  kv.substr(0, 80) + "'";
         return panel(ui)->CmdEdit(kv.substr(0, eq), kv.substr(eq + 1));
       }});
  row({.name = "revert",
       .args = {Offer(Text("KEY", "a tunable's key", ArgType::kWord), TunableKeys)},
       .menu = "Run/Revert a value…",
       .help = "Edit a tunable back to its value in the file (with --set)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) { return panel(ui)->CmdRevert(a.Text(0)); }});
  // The value entry, as the mouse and keyboard drive it (app/gui/value_entry.hpp).
  auto needs_field = [](const AppUi& ui) {
    return ui.Find<ParametersPanel>()->EntryKey().empty() ? std::string("no value field is open") : "";
  };
  row({.name = "field-open",
       .args = {Offer(Text("KEY", "a tunable's key (a number)", ArgType::kWord), TunableKeys)},
       .help = "Open the text entry of a tunable's field, as a double-click or Ctrl+click does",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) { return panel(ui)->CmdFieldOpen(a.Text(0)); },
       .script_only = true});
  row({.name = "field-type",
       .args = {Text("TEXT", "characters to type")},
       .help = "Type into the open field (nothing is applied until Enter)",
       .disabled = needs_field,
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) { return panel(ui)->CmdFieldType(a.Text(0)); },
       .script_only = true});
  row({.name = "field-enter",
       .help = "Enter in the open field: apply the value typed, or show why it is refused",
       .disabled = needs_field,
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdFieldKey(true); },
       .script_only = true});
  row({.name = "field-escape",
       .help = "Esc in the open field: close it, nothing applied",
       .disabled = needs_field,
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdFieldKey(false); },
       .script_only = true});
  row({.name = "field-wheel",
       .args = {Offer(Text("KEY", "a tunable's key (a number)", ArgType::kWord), TunableKeys),
                Whole("STEPS", -1000, 1000)},
       .help = "Turn the mouse wheel over a tunable's field: STEPS fine steps up (or down)",
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) {
         return panel(ui)->CmdFieldWheel(a.Text(0), static_cast<int>(a.Whole(1)));
       },
       .script_only = true});
  row({.name = "action",
       .args = {Offer(Text("ID", "an action of the scenario", ArgType::kWord), ActionIds)},
       .menu = "Run/Scenario action",
       .help = "Run an action the scenario offers (e.g. reload_rules), between two steps",
       .disabled = NeedsActions,
       .run = [panel](AppUi& ui, const CommandArgs& a, Src) { return panel(ui)->CmdAction(a.Text(0)); }});
  return t;
}

std::vector<Command> ParametersPanel::UndoRows() {
  using Src = CommandSource;
  auto panel = [](AppUi& ui) { return ui.Find<ParametersPanel>(); };
  std::vector<Command> t;
  auto row = [&t](Command c) { t.push_back(std::move(c)); };
  row({.name = "undo",
       .keys = {"Ctrl+Z"},
       .menu = "Compare/Undo",
       .help = "Undo the last edit or formation change",
       .disabled =
           [](const AppUi& ui) {
             return ui.session().can_undo() ? std::string() : std::string("nothing to undo");
           },
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdUndo(); }});
  row({.name = "redo",
       .keys = {"Ctrl+Y", "Ctrl+Shift+Z"},
       .menu = "Compare/Redo",
       .help = "Redo what was undone",
       .disabled =
           [](const AppUi& ui) {
             return ui.session().can_redo() ? std::string() : std::string("nothing to redo");
           },
       .run = [panel](AppUi& ui, const CommandArgs&, Src) { return panel(ui)->CmdRedo(); }});
  return t;
}

}  // namespace formsim::app
