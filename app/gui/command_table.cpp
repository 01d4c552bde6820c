#include "app/gui/command_table.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

std::string Trimmed(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && IsSpace(s[a])) ++a;
  while (b > a && IsSpace(s[b - 1])) --b;
  return s.substr(a, b - a);
}

// A refused argument's text, cut so that a 30,000-character argument makes a readable message.
std::string Quoted(const std::string& s) {
  constexpr std::size_t kMax = 80;
  if (s.size() <= kMax) return "'" + s + "'";
  return "'" + s.substr(0, kMax) + "…' (" + std::to_string(s.size()) + " characters)";
}

// Whole numbers as digits (1000000, not 1e+06).
std::string RangeText(double lo, double hi) {
  return sim::FormatWholeOrShortest(lo) + " ... " + sim::FormatWholeOrShortest(hi);
}

// `s` padded with spaces to `width` characters (UTF-8 aware: "…" is one).
std::string Padded(const std::string& s, std::size_t width) {
  std::size_t chars = 0;
  for (unsigned char c : s) chars += (c & 0xC0) != 0x80;
  return s + std::string(chars < width ? width - chars : 1, ' ');
}

std::string Joined(const std::vector<std::string>& v, const char* sep) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
  return out;
}

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// The argument's choices now: fixed, or the window's.
std::vector<std::string> ChoicesOf(const CommandArg& arg, const AppUi* ui) {
  if (!arg.choices.empty() || !arg.offer || ui == nullptr) return arg.choices;
  return arg.offer(*ui);
}

}  // namespace

std::string CommandArg::TypeText() const {
  std::string t;
  switch (type) {
    case ArgType::kWord:
    case ArgType::kRest:
      t = what.empty() ? "text" : what;
      break;
    case ArgType::kWhole:
      t = "a whole number in " + RangeText(lo, hi);
      break;
    case ArgType::kReal:
      t = "a number in " + RangeText(lo, hi);
      break;
    case ArgType::kOnOff:
      t = "on, off or toggle";
      break;
    case ArgType::kChoice:
      t = choices.empty() ? (what.empty() ? "one of the window's choices" : what)
                          : Joined(choices, ", ");
      break;
  }
  if (!unit.empty()) t += " (" + unit + ")";
  return t;
}

std::string Command::Usage() const {
  std::string u = name;
  for (const CommandArg& a : args) {
    std::string shown = a.name;
    if (a.type == ArgType::kOnOff)
      shown = "on|off|toggle";
    else if (a.type == ArgType::kChoice && !a.choices.empty() && a.choices.size() <= 6)
      shown = Joined(a.choices, "|");
    u += a.optional ? " [" + shown + "]" : " " + shown;
  }
  return u;
}

std::string Command::KeysText() const {
  return Joined(keys, ", ");
}

void SplitCommandLine(const std::string& line, std::string* action, std::string* rest) {
  const std::string t = Trimmed(line);
  std::size_t sp = 0;
  while (sp < t.size() && !IsSpace(t[sp])) ++sp;
  *action = t.substr(0, sp);
  *rest = Trimmed(t.substr(sp));
}

std::string ParseCommandArgs(const Command& cmd, const std::string& text, const AppUi* ui,
                             CommandArgs* out) {
  *out = CommandArgs();
  std::size_t pos = 0;
  auto skip = [&] {
    while (pos < text.size() && IsSpace(text[pos])) ++pos;
  };
  for (const CommandArg& arg : cmd.args) {
    skip();
    const std::string head = cmd.name + ": " + arg.name + " expects " + arg.TypeText();
    if (pos >= text.size()) {
      if (arg.optional) break;
      return head + ", got nothing";
    }
    std::string word;
    if (arg.type == ArgType::kRest) {
      word = Trimmed(text.substr(pos));
      pos = text.size();
    } else {
      const std::size_t start = pos;
      while (pos < text.size() && !IsSpace(text[pos])) ++pos;
      word = text.substr(start, pos - start);
    }
    double number = 0;
    switch (arg.type) {
      case ArgType::kWord:
      case ArgType::kRest:
        break;
      case ArgType::kWhole: {
        long long v = 0;
        if (!sim::ParseInteger(word, static_cast<long long>(arg.lo), static_cast<long long>(arg.hi),
                               &v))
          return head + ", got " + Quoted(word);
        number = static_cast<double>(v);
        break;
      }
      case ArgType::kReal:
        if (!sim::ParseFiniteDouble(word, &number) || number < arg.lo || number > arg.hi)
          return head + ", got " + Quoted(word);
        break;
      case ArgType::kOnOff:
        if (word == "on" || word == "true" || word == "1") {
          number = 1;
        } else if (word == "off" || word == "false" || word == "0") {
          number = 0;
        } else if (word == "toggle" && cmd.checked && ui != nullptr) {
          number = cmd.checked(*ui) ? 0 : 1;
        } else {
          return head + ", got " + Quoted(word);
        }
        word = number != 0 ? "on" : "off";
        break;
      case ArgType::kChoice: {
        const std::vector<std::string> choices = ChoicesOf(arg, ui);
        if (std::find(choices.begin(), choices.end(), word) == choices.end())
          return cmd.name + ": " + arg.name + " expects " +
                 (choices.empty() ? std::string("a choice, and there is none now")
                                  : Joined(choices, ", ")) +
                 ", got " + Quoted(word);
        break;
      }
    }
    out->text.push_back(word);
    out->number.push_back(number);
  }
  skip();
  if (pos < text.size())
    return cmd.name + ": unexpected " + Quoted(text.substr(pos)) + " (usage: " + cmd.Usage() + ")";
  return "";
}

const Command* FindCommand(const std::string& name) {
  for (const Command& c : Commands())
    if (c.name == name) return &c;
  return nullptr;
}

std::vector<std::string> ClosestCommands(const std::string& name, std::size_t n) {
  std::vector<std::pair<std::size_t, std::string>> scored;
  const std::string probe = name.substr(0, 64);  // a long typo costs no more than a short one
  for (const Command& c : Commands()) {
    std::size_t d = EditDistance(probe, c.name);
    // A shared start or one containing the other counts as close.
    if (!probe.empty() && (c.name.rfind(probe, 0) == 0 || c.name.find(probe) != std::string::npos))
      d = std::min<std::size_t>(d, 1);
    scored.emplace_back(d, c.name);
  }
  std::stable_sort(scored.begin(), scored.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (const auto& s : scored) {
    if (out.size() >= n) break;
    out.push_back(s.second);
  }
  return out;
}

std::string CommandListText() {
  std::string out;
  for (const Command& c : Commands()) {
    std::string args;
    for (const CommandArg& a : c.args)
      args += (args.empty() ? "" : "; ") + std::string(a.optional ? "[" : "") + a.name + ": " +
              a.TypeText() + (a.optional ? "]" : "");
    out += Padded(c.name, 17) + Padded(c.keys.empty() ? "-" : c.KeysText(), 22) +
           Padded(c.menu.empty() ? "(script only)" : c.menu, 36) + (args.empty() ? "-" : args) +
           "\n";
  }
  return out;
}

std::string CommandTableMarkdown() {
  std::string out =
      "| action | arguments | keys | menu | what it does |\n"
      "|---|---|---|---|---|\n";
  for (const Command& c : Commands()) {
    std::string args;
    for (const CommandArg& a : c.args)
      args += (args.empty() ? "" : "; ") + std::string(a.optional ? "[" : "") + "`" + a.name +
              "` " + a.TypeText() + (a.optional ? "]" : "");
    std::string keys;
    for (const std::string& k : c.keys) keys += (keys.empty() ? "" : ", ") + ("`" + k + "`");
    std::string help = c.help;
    std::string menu = c.menu;
    for (std::string* s : {&args, &help, &menu}) {
      std::string escaped;
      for (char ch : *s) escaped += ch == '|' ? std::string("\\|") : std::string(1, ch);
      *s = escaped;
    }
    out += "| `" + c.name + "` | " + (args.empty() ? "" : args) + " | " + keys + " | " +
           (menu.empty() ? "script only" : menu) + " | " + help + " |\n";
  }
  return out;
}

std::string CommandUsageList() {
  std::vector<std::string> usages;
  for (const Command& c : Commands()) usages.push_back(c.Usage());
  return Joined(usages, ", ");
}

std::vector<std::pair<std::string, std::string>> KeyHelpRows() {
  std::vector<std::pair<std::string, std::string>> rows;
  for (const Command& c : Commands())
    if (!c.keys.empty()) rows.emplace_back(c.KeysText(), c.help);
  return rows;
}

}  // namespace formsim::app
