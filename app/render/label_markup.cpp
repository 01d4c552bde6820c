#include "app/render/label_markup.hpp"

#include <cstring>

namespace formsim::app {
namespace {

struct Named {
  const char* name;
  const char* text;
};
// Greek letters by name, as in TeX.
constexpr Named kGreek[] = {
    {"alpha", "α"},  {"beta", "β"},   {"gamma", "γ"},   {"delta", "δ"}, {"epsilon", "ε"},
    {"zeta", "ζ"},   {"eta", "η"},    {"theta", "θ"},   {"iota", "ι"},  {"kappa", "κ"},
    {"lambda", "λ"}, {"mu", "μ"},     {"nu", "ν"},      {"xi", "ξ"},    {"pi", "π"},
    {"rho", "ρ"},    {"sigma", "σ"},  {"tau", "τ"},     {"upsilon", "υ"}, {"phi", "φ"},
    {"chi", "χ"},    {"psi", "ψ"},    {"omega", "ω"},   {"Gamma", "Γ"}, {"Delta", "Δ"},
    {"Theta", "Θ"},  {"Lambda", "Λ"}, {"Xi", "Ξ"},      {"Pi", "Π"},    {"Sigma", "Σ"},
    {"Phi", "Φ"},    {"Psi", "Ψ"},    {"Omega", "Ω"},
};

// The sub- or superscript form of one ASCII character, "" when Unicode (or the atlas) has none.
const char* Script(char c, bool sub) {
  static const char* const kSubDigits[] = {"₀", "₁", "₂", "₃", "₄", "₅", "₆", "₇", "₈", "₉"};
  static const char* const kSupDigits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  if (c >= '0' && c <= '9') return sub ? kSubDigits[c - '0'] : kSupDigits[c - '0'];
  if (sub) {
    switch (c) {
      case '+': return "₊";
      case '-': return "₋";
      case '=': return "₌";
      case '(': return "₍";
      case ')': return "₎";
      case 'a': return "ₐ";
      case 'e': return "ₑ";
      case 'o': return "ₒ";
      case 'x': return "ₓ";
      case 'h': return "ₕ";
      case 'k': return "ₖ";
      case 'l': return "ₗ";
      case 'm': return "ₘ";
      case 'n': return "ₙ";
      case 'p': return "ₚ";
      case 's': return "ₛ";
      case 't': return "ₜ";
      default: return "";
    }
  }
  switch (c) {
    case '+': return "⁺";
    case '-': return "⁻";
    case '=': return "⁼";
    case '(': return "⁽";
    case ')': return "⁾";
    case 'n': return "ⁿ";
    case 'i': return "ⁱ";
    default: return "";
  }
}

// `\name` at `i` (i at the backslash): its text and the length consumed, or 0.
std::size_t GreekAt(const std::string& s, std::size_t i, std::string* out) {
  std::size_t j = i + 1;
  while (j < s.size() && ((s[j] >= 'a' && s[j] <= 'z') || (s[j] >= 'A' && s[j] <= 'Z'))) ++j;
  const std::string name = s.substr(i + 1, j - i - 1);
  for (const Named& g : kGreek)
    if (name == g.name) {
      *out = g.text;
      return j - i;
    }
  return 0;
}

}  // namespace

std::string MarkupText(const std::string& label) {
  if (label.find_first_of("\\_^") == std::string::npos) return label;
  std::string out;
  out.reserve(label.size());
  for (std::size_t i = 0; i < label.size();) {
    const char c = label[i];
    std::string greek;
    if (c == '\\') {
      if (const std::size_t n = GreekAt(label, i, &greek)) {
        out += greek;
        i += n;
        continue;
      }
    } else if ((c == '_' || c == '^') && i + 1 < label.size() && label[i + 1] == '{') {
      const std::size_t close = label.find('}', i + 2);
      if (close != std::string::npos) {
        // The group's own text (Greek names inside resolved first), then scripts if all exist.
        const std::string inner = MarkupText(label.substr(i + 2, close - i - 2));
        std::string scripted;
        bool all = !inner.empty();
        for (char ch : inner) {
          const char* s = Script(ch, c == '_');
          if (!*s) {
            all = false;
            break;
          }
          scripted += s;
        }
        out += all ? scripted : std::string(1, c) + inner;
        i = close + 1;
        continue;
      }
    }
    out += c;
    ++i;
  }
  return out;
}

}  // namespace formsim::app
