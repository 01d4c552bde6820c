#include "app/gui/table_header.hpp"

#include <imgui.h>

#include "app/render/long_text.hpp"

namespace formsim::app {

std::string FitHeader(const std::string& label, float width,
                      const std::function<float(const std::string&)>& measure) {
  if (measure(label) <= width) return label;
  std::string name = label, unit;
  const auto open = label.rfind(" [");
  if (open != std::string::npos && !label.empty() && label.back() == ']') {
    name = label.substr(0, open);
    unit = label.substr(open);
  }
  const std::string ellipsis = "…";
  // Shorter and shorter at UTF-8 character boundaries (never inside a character).
  for (std::size_t n = name.size(); n > 0; --n) {
    if ((static_cast<unsigned char>(name[n]) & 0xC0) == 0x80) continue;
    const std::string cut = name.substr(0, n) + ellipsis + unit;
    if (measure(cut) <= width) return cut;
  }
  if (!unit.empty() && measure(ellipsis + unit) <= width) return ellipsis + unit;
  return ellipsis;
}

void TableHeaders(const std::vector<std::string>& labels, bool sortable) {
  ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
  const auto measure = [](const std::string& s) { return ImGui::CalcTextSize(s.c_str()).x; };
  for (int c = 0; c < static_cast<int>(labels.size()); ++c) {
    if (!ImGui::TableSetColumnIndex(c)) continue;
    const std::string& label = labels[c];
    // ImGui's header keeps room for the sort arrow and the cell's padding.
    const float room = ImGui::GetContentRegionAvail().x - (sortable ? ImGui::GetFontSize() : 0.0f);
    const std::string shown = FitHeader(label, room, measure);
    ImGui::PushID(c);
    // "###": the same ID whatever the text shown.
    ImGui::TableHeader((shown + "###h").c_str());
    ImGui::PopID();
    if (shown != label && ImGui::IsItemHovered()) SafeTooltip(label);
  }
}

void MarkBestCell() {
  ImGui::TableSetBgColor(ImGuiTableBgTarget_CellBg,
                         ImGui::GetColorU32(ImVec4(0.55f, 0.85f, 0.55f, 0.45f)));
}

}  // namespace formsim::app
