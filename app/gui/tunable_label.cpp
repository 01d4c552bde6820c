#include "app/gui/tunable_label.hpp"

#include <imgui_internal.h>

#include <cmath>
#include <vector>

#include "app/render/imgui_canvas.hpp"
#include "app/render/label_markup.hpp"
#include "sim/core/param_table.hpp"

namespace formsim::app {
namespace {

// The characters of a UTF-8 string (each as its bytes).
std::vector<std::string> Chars(const std::string& s) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < s.size();) {
    std::size_t n = 1;
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0xF0) n = 4;
    else if (c >= 0xE0) n = 3;
    else if (c >= 0xC0) n = 2;
    out.push_back(s.substr(i, n));
    i += n;
  }
  return out;
}

bool IsAsciiLetter(const std::string& c) {
  return c.size() == 1 && ((c[0] >= 'a' && c[0] <= 'z') || (c[0] >= 'A' && c[0] <= 'Z'));
}
bool IsDigit(const std::string& c) { return c.size() == 1 && c[0] >= '0' && c[0] <= '9'; }
// A Greek letter (U+0391 ... U+03C9): two bytes, 0xCE or 0xCF first.
bool IsGreek(const std::string& c) {
  return c.size() == 2 && (static_cast<unsigned char>(c[0]) == 0xCE ||
                           static_cast<unsigned char>(c[0]) == 0xCF);
}
bool IsLetter(const std::string& c) { return IsAsciiLetter(c) || IsGreek(c); }

// A symbol: one letter, then digits ("k", "φ", "l2", "P0"); `letter` and `digits` get its parts.
bool Symbol(const std::string& token, std::string* letter, std::string* digits) {
  const std::vector<std::string> c = Chars(token);
  if (c.empty() || !IsLetter(c[0])) return false;
  std::string d;
  for (std::size_t i = 1; i < c.size(); ++i) {
    if (!IsDigit(c[i])) return false;
    d += c[i];
  }
  *letter = c[0];
  *digits = d;
  return true;
}

// An index: at most three letters, digits or commas ("l1", "θ", "x,y", "max").
bool Index(const std::string& token) {
  const std::vector<std::string> c = Chars(token);
  if (c.empty() || c.size() > 3) return false;
  for (const std::string& ch : c)
    if (!IsLetter(ch) && !IsDigit(ch) && ch != ",") return false;
  return true;
}

std::string Sub(const std::string& letter, const std::string& index) {
  return EscapeMarkup(letter) + "_{" + EscapeMarkup(index) + "}";
}

std::vector<std::string> Split(const std::string& s) {
  std::vector<std::string> out;
  std::string w;
  for (char c : s) {
    if (c == ' ') {
      out.push_back(w);
      w.clear();
    } else {
      w += c;
    }
  }
  out.push_back(w);
  return out;
}

}  // namespace

std::string TunableLabelMarkup(const std::string& label) {
  const std::vector<std::string> words = Split(label);
  std::string letter, digits;
  if (words.size() == 2 && Symbol(words[0], &letter, &digits)) {
    const std::string tail = words[1] == "desired" ? "des" : words[1];
    // "k l1" -> k_{l1}, "P0 l" -> P_{0,l}, "l2 desired" -> l_{2,des}
    if (words[1] == "desired" || Index(words[1]))
      return Sub(letter, digits.empty() ? tail : digits + "," + tail);
  }
  if (words.size() == 1) {
    // "v_ref" -> v_{ref}
    const auto us = label.find('_');
    if (us != std::string::npos && Symbol(label.substr(0, us), &letter, &digits) && digits.empty() &&
        Index(label.substr(us + 1)))
      return Sub(letter, label.substr(us + 1));
  }
  // Otherwise word by word: a symbol with digits among words ("spiral R0") gets them as a
  // subscript; the rest as written.
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0) out += " ";
    if (words.size() > 1 && Symbol(words[i], &letter, &digits) && !digits.empty())
      out += Sub(letter, digits);
    else
      out += EscapeMarkup(words[i]);
  }
  return out;
}

std::string TunableLabel(const sim::Param& p) {
  return p.tune.label.empty() ? EscapeMarkup(p.key) : TunableLabelMarkup(p.tune.label);
}

float MarkupTextWidth(const std::string& markup) {
  return MarkupRunsWidth(ImGui::GetFont(), ImGui::GetFontSize(), markup);
}

void MarkupTextItem(const std::string& markup, ImVec4 color) {
  ImGuiWindow* window = ImGui::GetCurrentWindow();
  if (window->SkipItems) return;
  ImFont* f = ImGui::GetFont();
  const float size = ImGui::GetFontSize();
  const ImVec2 pos(window->DC.CursorPos.x, window->DC.CursorPos.y + window->DC.CurrLineTextBaseOffset);
  const ImRect bb(pos, ImVec2(pos.x + MarkupTextWidth(markup), pos.y + size));
  ImGui::ItemSize(bb.GetSize(), 0.0f);
  if (!ImGui::ItemAdd(bb, 0)) return;
  const ImU32 col = color.w > 0 ? ImGui::GetColorU32(color) : ImGui::GetColorU32(ImGuiCol_Text);
  DrawMarkupRuns(window->DrawList, f, size, pos, col, markup, 1.0f, false);
}

std::string FitMarkupLabel(const std::string& name, const std::string& suffix, float width) {
  const std::string tail = EscapeMarkup(suffix);
  if (MarkupTextWidth(name + tail) <= width) return name + tail;
  for (std::size_t n = name.size(); n > 0; --n) {
    const std::string cut = ShortenMarkup(name, n) + tail;
    if (cut != name + tail && MarkupTextWidth(cut) <= width) return cut;
  }
  if (!suffix.empty() && MarkupTextWidth(EscapeMarkup("…" + suffix)) <= width)
    return EscapeMarkup("…" + suffix);
  return "…";
}

}  // namespace formsim::app
