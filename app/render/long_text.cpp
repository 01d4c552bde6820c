#include "app/render/long_text.hpp"

#include <imgui.h>

#include <algorithm>
#include <vector>

namespace formsim::app {
namespace {

// Bytes per line of the scrolling view: lines are cut there (and at every newline), so each
// visible line costs at most this many glyphs.
constexpr std::size_t kLineBytes = 160;
constexpr std::size_t kTooltipBytes = 3000;

bool Continuation(unsigned char c) {
  return (c & 0xC0) == 0x80;
}

// The largest cut <= n that does not split a UTF-8 character.
std::size_t CutAt(const std::string& s, std::size_t from, std::size_t n) {
  std::size_t end = std::min(s.size(), from + n);
  while (end > from && end < s.size() && Continuation(static_cast<unsigned char>(s[end]))) --end;
  return end == from ? std::min(s.size(), from + n) : end;
}

// Line starts of `text`: at each newline, and every kLineBytes bytes of a longer line.
std::vector<std::size_t> Lines(const std::string& text) {
  std::vector<std::size_t> starts;
  std::size_t pos = 0;
  while (pos < text.size()) {
    starts.push_back(pos);
    const std::size_t nl = text.find('\n', pos);
    const std::size_t line_end = nl == std::string::npos ? text.size() : nl;
    const std::size_t cut = CutAt(text, pos, kLineBytes);
    pos = cut < line_end ? cut : line_end + 1;
  }
  return starts;
}

// `text` wrapped to the content region at spaces only: ImGui's own wrap also breaks after
// '.' and ',', which splits a number ("0." / "99") at a large UI scale. A word wider than the
// whole line is left to ImGui's wrap.
void WrapAtSpaces(const std::string& text) {
  const float width = std::max(1.0f, ImGui::GetContentRegionAvail().x);
  ImFont* font = ImGui::GetFont();
  const float size = ImGui::GetFontSize();
  auto wide = [&](const char* b, const char* e) { return font->CalcTextSizeA(size, 1e30f, 0.0f, b, e).x; };
  const char* p = text.c_str();
  const char* const end = p + text.size();
  while (p <= end) {
    const char* nl = std::find(p, end, '\n');
    // One paragraph [p, nl): lines of whole words.
    const char* line = p;
    while (line < nl) {
      const char* fit_end = nullptr;  // the end of the last word that fits
      const char* q = line;
      while (q < nl) {
        const char* word_end = std::find(q, nl, ' ');
        if (fit_end != nullptr && wide(line, word_end) > width) break;
        fit_end = word_end;
        q = word_end < nl ? word_end + 1 : nl;
      }
      if (fit_end != nullptr && wide(line, fit_end) > width) {
        // One word wider than the line: ImGui's wrap (any break beats text past the edge).
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(line, fit_end);
        ImGui::PopTextWrapPos();
      } else {
        ImGui::TextUnformatted(line, fit_end);
      }
      line = fit_end;
      while (line < nl && *line == ' ') ++line;
    }
    if (nl == p) ImGui::TextUnformatted("");  // an empty line keeps its height
    p = nl + 1;
  }
}

}  // namespace

std::string Shorten(const std::string& text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return text;
  return text.substr(0, CutAt(text, 0, max_bytes)) + "…";
}

void LongTextWrapped(const char* id, const std::string& text, std::size_t inline_bytes) {
  if (text.size() <= inline_bytes) {
    WrapAtSpaces(text);
    return;
  }
  WrapAtSpaces(Shorten(text, inline_bytes));
  ImGui::PushID(id);
  const std::string label = "whole text (" + std::to_string(text.size()) + " bytes)";
  if (ImGui::TreeNode("##whole", "%s", label.c_str())) {
    const float h = std::min(300.0f, 12 * ImGui::GetTextLineHeightWithSpacing());
    if (ImGui::BeginChild("##scroll", ImVec2(0, h), true, ImGuiWindowFlags_HorizontalScrollbar)) {
      const std::vector<std::size_t> starts = Lines(text);
      ImGuiListClipper clipper;
      clipper.Begin(static_cast<int>(starts.size()));
      while (clipper.Step())
        for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
          const std::size_t b = starts[static_cast<std::size_t>(i)];
          std::size_t e = i + 1 < static_cast<int>(starts.size())
                              ? starts[static_cast<std::size_t>(i) + 1]
                              : text.size();
          if (e > b && text[e - 1] == '\n') --e;
          ImGui::TextUnformatted(text.c_str() + b, text.c_str() + e);
        }
      clipper.End();
    }
    ImGui::EndChild();
    ImGui::TreePop();
  }
  ImGui::PopID();
}

void SafeTooltip(const std::string& text) {
  const std::string shown = Shorten(text, kTooltipBytes);
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
  ImGui::TextUnformatted(shown.c_str(), shown.c_str() + shown.size());
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

}  // namespace formsim::app
