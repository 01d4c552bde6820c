/// \file The generic parameter panel: every entry of the experiment's ParamTable, grouped by its
/// group path ("Gains/R2" -> header "Gains", node "R2"). Widgets never write the experiment:
/// they queue edits in the Session, applied between steps.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "app/ui.hpp"

namespace formsim::app {
namespace {

std::string Head(const std::string& group) {
  return group.substr(0, group.find('/'));
}
std::string Tail(const std::string& group) {
  const auto slash = group.find('/');
  return slash == std::string::npos ? "" : group.substr(slash + 1);
}

// One row: label (with unit) on the left, widget on the right. Returns the new value as text when
// the user changed it, "" otherwise.
std::string ParamRow(const sim::Param& p, const std::string* waiting) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::AlignTextToFramePadding();
  std::string label = p.label.empty() ? p.key : p.label;
  if (!p.unit.empty()) label += " [" + p.unit + "]";
  ImGui::TextUnformatted(label.c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s\nrange %g … %g%s%s", p.key.c_str(), p.min, p.max,
                      p.log_scale ? ", log scale" : "",
                      p.requires_reset ? "\napplies on reset" : "\napplies on the next step");
  ImGui::TableSetColumnIndex(1);
  ImGui::SetNextItemWidth(waiting ? -22.0f : -1.0f);
  ImGui::PushID(p.key.c_str());
  std::string out;
  switch (p.kind) {
    case sim::Param::Kind::kDouble: {
      double v = waiting ? std::atof(waiting->c_str()) : *p.d;
      // YAML may hold values outside the slider range: widen it rather than clamp them away.
      double lo = std::min(p.min, v), hi = std::max(p.max, v);
      ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
      if (p.log_scale && lo > 0) flags |= ImGuiSliderFlags_Logarithmic;
      if (ImGui::SliderScalar("##v", ImGuiDataType_Double, &v, &lo, &hi, "%.4g", flags) &&
          std::isfinite(v))
        out = ExactDouble(std::clamp(v, lo, hi));
      break;
    }
    case sim::Param::Kind::kInt: {
      int v = waiting ? std::atoi(waiting->c_str()) : *p.i;
      int lo = std::min(static_cast<int>(p.min), v), hi = std::max(static_cast<int>(p.max), v);
      if (ImGui::SliderInt("##v", &v, lo, hi, "%d", ImGuiSliderFlags_AlwaysClamp))
        out = std::to_string(std::clamp(v, lo, hi));
      break;
    }
    case sim::Param::Kind::kBool: {
      bool v = waiting ? (*waiting == "true") : *p.b;
      if (ImGui::Checkbox("##v", &v)) out = v ? "true" : "false";
      break;
    }
    case sim::Param::Kind::kChoice: {
      int cur = *p.i;
      if (waiting) {
        for (std::size_t k = 0; k < p.choices.size(); ++k)
          if (p.choices[k] == *waiting) cur = static_cast<int>(k);
      }
      const char* preview =
          cur >= 0 && cur < static_cast<int>(p.choices.size()) ? p.choices[cur].c_str() : "?";
      if (ImGui::BeginCombo("##v", preview)) {
        for (std::size_t k = 0; k < p.choices.size(); ++k)
          if (ImGui::Selectable(p.choices[k].c_str(), static_cast<int>(k) == cur) &&
              static_cast<int>(k) != cur)
            out = p.choices[k];
        ImGui::EndCombo();
      }
      break;
    }
  }
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
  auto& params = session_->exp().params().all();
  // Groups in order of first appearance; within a head group, sub-groups likewise.
  std::vector<std::string> heads;
  std::map<std::string, std::vector<std::string>> tails;
  for (const auto& p : params) {
    const std::string h = Head(p.group), t = Tail(p.group);
    if (std::find(heads.begin(), heads.end(), h) == heads.end()) heads.push_back(h);
    auto& v = tails[h];
    if (std::find(v.begin(), v.end(), t) == v.end()) v.push_back(t);
  }
  std::vector<std::pair<std::string, std::string>> edits;
  const auto& waiting = session_->waiting_for_reset();
  for (const std::string& h : heads) {
    const std::string header = (h.empty() ? std::string("Parameters") : h) + "###grp_" + h;
    if (!ImGui::CollapsingHeader(header.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) continue;
    for (const std::string& t : tails[h]) {
      const std::string group = t.empty() ? h : h + "/" + t;
      bool open = true;
      if (!t.empty())
        open = ImGui::TreeNodeEx((t + "##" + group).c_str(), ImGuiTreeNodeFlags_DefaultOpen);
      if (!open) continue;
      if (ImGui::BeginTable(("##tbl" + group).c_str(), 2, ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("label", ImGuiTableColumnFlags_WidthStretch, 0.45f);
        ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch, 0.55f);
        for (const auto& p : params) {
          if (p.group != group) continue;
          const auto w = waiting.find(p.key);
          const std::string v = ParamRow(p, w == waiting.end() ? nullptr : &w->second);
          if (!v.empty()) edits.emplace_back(p.key, v);
        }
        ImGui::EndTable();
      }
      if (!t.empty()) ImGui::TreePop();
    }
  }
  // Queued after the loop: an edit never changes the table while we iterate over it.
  for (const auto& [key, value] : edits) session_->Edit(key, value);
}

}  // namespace formsim::app
