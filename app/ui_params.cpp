/// \file The generic parameter panel: every tunable of the scenario's ParamTable (declared once,
/// where the scenario reader reads it), grouped by its group path ("Gains/R2" -> header
/// "Gains", node "R2"), plus the experiment's action buttons. Widgets never write the
/// experiment: they ask the session for an edit, which checks it against the whole scenario and
/// applies it between steps; a refused edit is marked at its widget with the reason.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include "app/ui.hpp"
#include "sim/core/number_format.hpp"

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

// One row: label (with unit) on the left, widget on the right. `shown` is the value to show (the
// one waiting for a reset, if any). Returns the new value as text when the user changed it.
std::string ParamRow(const sim::Param& p, const std::string& shown, bool waiting,
                     const std::string& refusal) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::AlignTextToFramePadding();
  std::string label = p.tune.label.empty() ? p.key : p.tune.label;
  if (!p.tune.unit.empty()) label += " [" + p.tune.unit + "]";
  if (!refusal.empty()) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.75f, 0.1f, 0.1f, 1));
  ImGui::TextUnformatted(label.c_str());
  if (!refusal.empty()) ImGui::PopStyleColor();
  if (ImGui::IsItemHovered()) {
    std::string tip = p.key;
    if (!p.tune.help.empty()) tip += "\n" + p.tune.help;
    if (p.kind == sim::Param::Kind::kDouble || p.kind == sim::Param::Kind::kInt)
      tip += "\nvalid: " + p.tune.ValidityText();
    tip += p.tune.live ? "\napplies on the next step" : "\napplies on reset";
    if (!refusal.empty()) tip += "\n\nlast edit refused: " + refusal;
    ImGui::SetTooltip("%s", tip.c_str());
  }
  ImGui::TableSetColumnIndex(1);
  ImGui::SetNextItemWidth(waiting ? -22.0f : -1.0f);
  ImGui::PushID(p.key.c_str());
  if (!refusal.empty()) ImGui::PushStyleColor(ImGuiCol_FrameBg, ImVec4(0.95f, 0.75f, 0.75f, 1));
  std::string out;
  switch (p.kind) {
    case sim::Param::Kind::kDouble: {
      double v = 0;
      if (!sim::ParseFiniteDouble(shown, &v)) v = p.value;
      // The declared slider range lies inside the validity; a file value outside the slider
      // widens it (still valid: the range between two valid values is valid).
      double lo = std::min(p.slider_min(), v), hi = std::max(p.slider_max(), v);
      ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
      if (p.tune.log_scale && lo > 0) flags |= ImGuiSliderFlags_Logarithmic;
      if (ImGui::SliderScalar("##v", ImGuiDataType_Double, &v, &lo, &hi, "%.4g", flags) &&
          std::isfinite(v))
        out = sim::FormatDouble(std::clamp(v, lo, hi));
      break;
    }
    case sim::Param::Kind::kInt: {
      long long parsed = 0;
      int v = sim::ParseInteger(shown, -2147483647LL, 2147483647LL, &parsed) ? static_cast<int>(parsed)
                                                                          : static_cast<int>(p.value);
      int lo = std::min(static_cast<int>(std::max(p.slider_min(), -1e9)), v);
      int hi = std::max(static_cast<int>(std::min(p.slider_max(), 1e9)), v);
      if (ImGui::SliderInt("##v", &v, lo, hi, "%d", ImGuiSliderFlags_AlwaysClamp))
        out = std::to_string(std::clamp(v, lo, hi));
      break;
    }
    case sim::Param::Kind::kBool: {
      bool v = shown == "true";
      if (ImGui::Checkbox("##v", &v)) out = v ? "true" : "false";
      break;
    }
    case sim::Param::Kind::kChoice: {
      if (ImGui::BeginCombo("##v", shown.c_str())) {
        for (const auto& c : p.choices)
          if (ImGui::Selectable(c.c_str(), c == shown) && c != shown) out = c;
        ImGui::EndCombo();
      }
      break;
    }
  }
  if (!refusal.empty()) ImGui::PopStyleColor();
  if (waiting) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(0.8f, 0.45f, 0.0f, 1.0f), "↻");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("changed: applies on reset (r)");
  }
  ImGui::PopID();
  return out;
}

}  // namespace

void AppUi::DrawParamSection() {
  const auto& params = session_->params().all();
  const auto actions = session_->exp().Actions();
  // Groups in order of first appearance; within a head group, sub-groups likewise. One pass
  // over the parameters (a thousand robots declare tens of thousands in thousands of groups).
  std::vector<std::string> heads;
  std::unordered_map<std::string, std::vector<std::string>> tails;
  std::unordered_set<std::string> seen;
  std::unordered_map<std::string, std::vector<const sim::Param*>> members;
  auto note_group = [&](const std::string& g) {
    if (!seen.insert(g).second) return;
    const std::string h = Head(g), t = Tail(g);
    const auto [it, fresh] = tails.try_emplace(h);
    if (fresh) heads.push_back(h);
    if (std::find(it->second.begin(), it->second.end(), t) == it->second.end()) it->second.push_back(t);
  };
  for (const auto& p : params) {
    note_group(p.tune.group);
    members[p.tune.group].push_back(&p);
  }
  for (const auto& a : actions) note_group(a.group);
  std::vector<std::pair<std::string, std::string>> edits;
  std::vector<std::string> run_actions;
  const auto waiting = session_->waiting_for_reset();
  for (const std::string& h : heads) {
    const std::string header = (h.empty() ? std::string("Parameters") : h) + "###grp_" + h;
    if (!ImGui::CollapsingHeader(header.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) continue;
    // Sub-groups start open unless there are many (one per robot of a swarm).
    const auto& subgroups = tails[h];
    const ImGuiTreeNodeFlags node_flags =
        subgroups.size() <= kOpenSubgroups ? ImGuiTreeNodeFlags_DefaultOpen : 0;
    for (const std::string& t : subgroups) {
      const std::string group = t.empty() ? h : h + "/" + t;
      bool open = true;
      if (!t.empty()) open = ImGui::TreeNodeEx((t + "##" + group).c_str(), node_flags);
      if (!open) continue;
      const auto in_group = members.find(group);
      if (in_group != members.end() &&
          ImGui::BeginTable(("##tbl" + group).c_str(), 2, ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("label", ImGuiTableColumnFlags_WidthStretch, 0.45f);
        ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch, 0.55f);
        for (const sim::Param* p : in_group->second) {
          const auto w = waiting.find(p->key);
          const bool is_waiting = w != waiting.end();
          const std::string v =
              ParamRow(*p, is_waiting ? w->second : p->Text(), is_waiting, session_->refusal(p->key));
          if (!v.empty()) edits.emplace_back(p->key, v);
        }
        ImGui::EndTable();
      }
      for (const auto& a : actions) {
        if (a.group != group) continue;
        if (ImGui::Button(a.label.c_str())) run_actions.push_back(a.id);
        if (!a.help.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", a.help.c_str());
      }
      if (!t.empty()) ImGui::TreePop();
    }
  }
  // Asked for after the loop: an edit never changes the table while we iterate over it.
  for (const auto& [key, value] : edits) CmdEdit(key, value);
  for (const auto& id : run_actions) CmdAction(id);
}

}  // namespace formsim::app
