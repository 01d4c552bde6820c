#include "app/render/label_markup.hpp"

namespace formsim::app {
namespace {

constexpr float kScriptScale = 0.7f;  // of the label's font size: sub- and superscripts

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

// A script run in Unicode sub- or superscript characters; "" when one has none (or the run is
// normal text).
std::string UnicodeScript(const MarkupRun& run) {
  if (run.kind == ScriptKind::kNormal) return "";
  std::string out;
  for (char ch : run.text) {
    const char* s = Script(ch, run.kind == ScriptKind::kSub);
    if (!*s) return "";
    out += s;
  }
  return out;
}

bool IsLetter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}

const char* GreekOf(const std::string& name) {
  for (const Named& g : kGreek)
    if (name == g.name) return g.text;
  return nullptr;
}

bool IsEscapable(char c) {
  return c == '\\' || c == '_' || c == '^' || c == '{' || c == '}';
}

void Append(std::vector<MarkupRun>& runs, ScriptKind kind, const std::string& text) {
  if (text.empty()) return;
  if (!runs.empty() && runs.back().kind == kind)
    runs.back().text += text;
  else
    runs.push_back({kind, text});
}

// Reads one `\...` at s[i] (the backslash) into `out`; returns the length consumed. An unknown
// command is written as it stands and reported in `error` (the first problem only).
std::size_t Command(const std::string& s, std::size_t i, std::string* out, std::string* error) {
  if (i + 1 < s.size() && IsEscapable(s[i + 1])) {
    *out = std::string(1, s[i + 1]);
    return 2;
  }
  std::size_t j = i + 1;
  while (j < s.size() && IsLetter(s[j])) ++j;
  const std::string name = s.substr(i + 1, j - i - 1);
  if (const char* g = GreekOf(name)) {
    *out = g;
    return j - i;
  }
  if (error->empty())
    *error = name.empty() ? std::string("a lone '\\' (write '\\\\' for a backslash)")
                          : "unknown markup command '\\" + name + "'";
  *out = s.substr(i, j - i);
  return j - i;
}

// The index of the '}' closing the group opened at s[open], nested braces and escapes counted;
// npos when it is not closed.
std::size_t GroupEnd(const std::string& s, std::size_t open) {
  int depth = 0;
  for (std::size_t i = open; i < s.size(); ++i) {
    if (s[i] == '\\') {
      ++i;
    } else if (s[i] == '{') {
      ++depth;
    } else if (s[i] == '}' && --depth == 0) {
      return i;
    }
  }
  return std::string::npos;
}

// The text of a script group s[b, e): commands resolved, inner braces only grouping, and an
// inner script flattened into the group's own (one level of scripts is drawn).
std::string GroupText(const std::string& s, std::size_t b, std::size_t e, std::string* error) {
  std::string out;
  for (std::size_t i = b; i < e;) {
    const char c = s[i];
    if (c == '\\') {
      std::string piece;
      i += Command(s, i, &piece, error);
      out += piece;
    } else if (c == '{' || c == '}' || ((c == '_' || c == '^') && i + 1 < e && s[i + 1] == '{')) {
      ++i;
    } else {
      out += c;
      ++i;
    }
  }
  return out;
}

}  // namespace

ParsedMarkup ParseMarkup(const std::string& label) {
  ParsedMarkup p;
  std::string normal;
  for (std::size_t i = 0; i < label.size();) {
    const char c = label[i];
    if (c == '\\') {
      std::string piece;
      i += Command(label, i, &piece, &p.error);
      normal += piece;
      continue;
    }
    if ((c == '_' || c == '^') && i + 1 < label.size() && label[i + 1] == '{') {
      const std::size_t close = GroupEnd(label, i + 1);
      if (close == std::string::npos) {
        if (p.error.empty())
          p.error = std::string("'") + c + "{' without its closing '}' (write '\\" + c +
                    "' for the character itself)";
        normal += label.substr(i);
        break;
      }
      Append(p.runs, ScriptKind::kNormal, normal);
      normal.clear();
      Append(p.runs, c == '_' ? ScriptKind::kSub : ScriptKind::kSuper,
             GroupText(label, i + 2, close, &p.error));
      i = close + 1;
      continue;
    }
    normal += c;
    ++i;
  }
  Append(p.runs, ScriptKind::kNormal, normal);
  return p;
}

std::string MarkupAccepted() {
  std::string greek;
  for (const Named& g : kGreek) greek += std::string(greek.empty() ? "" : " ") + "\\" + g.name;
  return "Greek letters by name (" + greek +
         "), x_{sub}, x^{super}, and \\\\ \\_ \\^ \\{ \\} for the characters themselves";
}

std::string MarkupError(const std::string& label) {
  const ParsedMarkup p = ParseMarkup(label);
  if (p.error.empty()) return "";
  return p.error + " in '" + label + "' (accepted: " + MarkupAccepted() + ")";
}

std::string EscapeMarkup(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (IsEscapable(c)) out += '\\';
    out += c;
  }
  return out;
}

std::string RunsMarkup(const std::vector<MarkupRun>& runs) {
  std::string out;
  for (const MarkupRun& r : runs) {
    if (r.kind == ScriptKind::kNormal)
      out += EscapeMarkup(r.text);
    else
      out += (r.kind == ScriptKind::kSub ? "_{" : "^{") + EscapeMarkup(r.text) + "}";
  }
  return out;
}

std::string ShortenMarkup(const std::string& label, std::size_t max_bytes) {
  std::vector<MarkupRun> runs = ParseMarkup(label).runs;
  std::size_t total = 0;
  for (const MarkupRun& r : runs) total += r.text.size();
  if (total <= max_bytes) return label;
  std::vector<MarkupRun> kept;
  std::size_t left = max_bytes;
  for (MarkupRun& r : runs) {
    if (r.text.size() > left) {
      std::size_t cut = left;  // not inside a UTF-8 sequence
      while (cut > 0 && (static_cast<unsigned char>(r.text[cut]) & 0xC0) == 0x80) --cut;
      r.text.resize(cut);
      left = 0;
    } else {
      left -= r.text.size();
    }
    if (!r.text.empty()) kept.push_back(std::move(r));
    if (left == 0) break;
  }
  Append(kept, ScriptKind::kNormal, "…");
  return RunsMarkup(kept);
}

RunPlacement PlacementOf(ScriptKind kind) {
  switch (kind) {
    case ScriptKind::kSub:
      return {kScriptScale, 0.2f};
    case ScriptKind::kSuper:
      return {kScriptScale, -0.38f};
    case ScriptKind::kNormal:
      break;
  }
  return {};
}

std::vector<MarkupRun> AtlasRuns(const std::string& label) {
  std::vector<MarkupRun> out;
  for (MarkupRun& run : ParseMarkup(label).runs) {
    const std::string u = UnicodeScript(run);
    if (u.empty())
      Append(out, run.kind, run.text);
    else
      Append(out, ScriptKind::kNormal, u);
  }
  return out;
}

std::string PlainText(const std::string& label) {
  std::string out;
  for (const MarkupRun& run : AtlasRuns(label)) out += run.text;
  return out;
}

std::string MarkupText(const std::string& label) {
  if (label.find_first_of("\\_^") == std::string::npos) return label;
  std::string out;
  for (const MarkupRun& run : AtlasRuns(label))
    out += run.kind == ScriptKind::kNormal ? run.text
                                           : (run.kind == ScriptKind::kSub ? "_" : "^") + run.text;
  return out;
}

}  // namespace formsim::app
