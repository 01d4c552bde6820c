#include "app/export/figure_titles.hpp"

#include <cctype>
#include <stdexcept>

namespace formsim::app {
namespace {

// The length of a leading panel label: "(b) " or "Fig. 9: " / "Fig. 6a: " (0: none).
std::size_t PanelPrefix(const std::string& t) {
  if (t.size() >= 4 && t[0] == '(' && std::isalpha(static_cast<unsigned char>(t[1])) &&
      t[2] == ')' && t[3] == ' ')
    return 4;
  if (t.rfind("Fig. ", 0) == 0) {
    std::size_t i = 5;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i;
    if (i < t.size() && std::isalpha(static_cast<unsigned char>(t[i]))) ++i;
    if (i > 5 && t.compare(i, 2, ": ") == 0) return i + 2;
  }
  return 0;
}

}  // namespace

const char* TitleModeNames() {
  return "full|short|none";
}

std::string TitleModeHelp() {
  return std::string("Figure titles: ") + TitleModeNames() +
         " (default full; short drops the panel letter and a closing (detail), none has no title)";
}

TitleMode ParseTitleMode(const std::string& text, const std::string& flag) {
  if (text == "full") return TitleMode::kFull;
  if (text == "short") return TitleMode::kShort;
  if (text == "none") return TitleMode::kNone;
  throw std::runtime_error(flag + " '" + text + "': expected one of " + TitleModeNames());
}

std::string TitleFor(const std::string& title, TitleMode mode) {
  if (mode == TitleMode::kFull) return title;
  if (mode == TitleMode::kNone) return "";
  std::string t = title.substr(PanelPrefix(title));
  // A closing "(...)" of detail, when something is left before it.
  if (!t.empty() && t.back() == ')') {
    int depth = 0;
    for (std::size_t i = t.size(); i-- > 0;) {
      if (t[i] == ')') ++depth;
      if (t[i] == '(' && --depth == 0) {
        if (i > 1 && t[i - 1] == ' ') t.erase(i - 1);
        break;
      }
    }
  }
  return t;
}

}  // namespace formsim::app
