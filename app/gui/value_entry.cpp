#include "app/gui/value_entry.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "app/render/display_unit.hpp"
#include "app/render/long_text.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {

void ValueEntry::Open(const std::string& key, const std::string& text) {
  key_ = key;
  opened_ = text;
  buf_[text.copy(buf_, sizeof buf_ - 1)] = '\0';  // cut to the field, always terminated
  focus_ = true;
  refusal_.clear();
}

void ValueEntry::Refused(const std::string& why) {
  refusal_ = why;
  focus_ = true;  // back to typing
}

void ValueEntry::Close() {
  key_.clear();
  opened_.clear();
  buf_[0] = '\0';
  focus_ = false;
  refusal_.clear();
}

bool ValueEntry::DrawnThisFrame() const {
  return !key_.empty() && drawn_frame_ == ImGui::GetFrameCount();
}

ValueEntry::Outcome ValueEntry::Draw() {
  drawn_frame_ = ImGui::GetFrameCount();
  if (focus_) {
    ImGui::SetKeyboardFocusHere();
    focus_ = false;
  }
  const bool red = !refusal_.empty();
  if (red) {
    ImGui::PushStyleColor(ImGuiCol_FrameBg, ImVec4(0.95f, 0.72f, 0.72f, 1));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.6f, 0.0f, 0.0f, 1));
  }
  // EnterReturnsTrue: the text is handed over on Enter only, never per keystroke.
  const bool enter =
      ImGui::InputText("##entry", buf_, sizeof buf_,
                       ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll |
                           ImGuiInputTextFlags_CharsScientific);
  // Esc reverts ImGui's text and lets go; so does a click elsewhere: both cancel.
  const bool let_go = ImGui::IsItemDeactivated();
  if (red) ImGui::PopStyleColor(2);
  if (ImGui::IsItemHovered())
    SafeTooltip(red ? "refused: " + refusal_ + "\nEnter commits another value, Esc cancels"
                    : std::string("Enter commits, Esc cancels"));
  if (enter) return Outcome::kCommit;
  return let_go ? Outcome::kCancel : Outcome::kNone;
}

std::string ValueEntry::StoredText(double scale) const {
  std::string typed = buf_;
  typed.erase(0, typed.find_first_not_of(' '));
  typed.erase(typed.find_last_not_of(' ') + 1);
  double t = 0;
  if (scale != 1.0 && sim::ParseFiniteDouble(typed, &t)) return sim::FormatDouble(t / scale);
  return typed.empty() ? std::string(buf_) : typed;
}

std::string ParamEntryText(const sim::Param& p, const std::string& shown, bool degrees) {
  const DisplayUnit du = ShownUnit(p.tune.unit, degrees);
  double v = 0;
  if (du.scale == 1.0 || p.kind != sim::Param::Kind::kDouble || !sim::ParseFiniteDouble(shown, &v))
    return shown;
  return sim::FormatSignificant(v * du.scale, 6);
}

std::string FineStep(const sim::Param& p, double value, int steps, double scale) {
  const double lo = std::min(p.slider_min(), value), hi = std::max(p.slider_max(), value);
  if (p.kind == sim::Param::Kind::kInt) {
    const double v = std::clamp(std::round(value) + steps, std::ceil(lo), std::floor(hi));
    return sim::FormatDouble(v);
  }
  const double shown = value * scale;
  const double span = p.tune.log_scale && lo > 0 && value > 0 ? std::abs(shown) : (hi - lo) * scale;
  if (!(span > 0) || !std::isfinite(span)) return sim::FormatDouble(value);
  const double step = std::pow(10.0, std::floor(std::log10(span / 100.0)));
  // Snapped to the step's grid, then written with no more digits than the step has.
  const double next = std::round(shown / step + steps) * step;
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  double snapped = 0;
  if (!sim::ParseFiniteDouble(sim::FormatFixed(next, decimals), &snapped)) snapped = next;
  // Back in the stored unit (an angle of whole degrees keeps every digit of its radians).
  return sim::FormatDouble(std::clamp(snapped / scale, lo, hi));
}

}  // namespace formsim::app
