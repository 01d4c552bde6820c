#include "sim/scenario/lesson.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <set>

#include "sim/core/number_format.hpp"

namespace formsim::sim {
namespace {

using Check = LessonCheck;

constexpr const char* kStatNames[] = {"max_abs", "max",    "min",         "mean", "rms",
                                      "jitter",  "first_below", "tau", "final"};
constexpr const char* kRelationNames[] = {"less", "greater", "within", "equal", "about"};

std::string FormatRangeEnd(double v) {
  if (std::isinf(v)) return v > 0 ? "+inf" : "-inf";
  return FormatSignificant(v);
}

bool IsCheckId(const std::string& s) {
  if (s.empty() || s.size() > 64 || !(s[0] >= 'a' && s[0] <= 'z')) return false;
  for (char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

// A relation's operand: a number, or the id of another check.
void ReadOperand(YamlReader& c, const std::string& key, Check& out) {
  const YAML::Node n = c.Raw(key);
  if (!n.IsScalar()) c.Fail(key, "expected a number or the id of a check");
  const std::string& s = n.Scalar();
  if (IsCheckId(s)) {
    out.against = s;
    return;
  }
  out.value = c.Double(key, 0.0);
}

Check ReadCheck(YamlReader& c) {
  Check k;
  k.line = c.node().Mark().line + 1;
  k.id = c.RequiredString("id");
  if (!IsCheckId(k.id)) c.Fail("id", "must be [a-z][a-z0-9_]* (at most 64 characters)");
  k.sets = c.Strings("set", {});
  for (const std::string& s : k.sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
      c.Fail("set", "an edit must be path.to.key=value, got '" + s + "'");
  }
  if (c.Has("duration")) k.duration = c.Double("duration", 0.0, Tune("duration", "s").Above(0).AtMost(1e6));

  const int sources = c.Has("metric") + c.Has("events") + c.Has("column");
  if (sources != 1) c.Fail("id", "a check measures exactly one of metric, events, column");
  if (c.Has("metric")) {
    k.source = Check::Source::kMetric;
    k.name = c.RequiredString("metric");
  } else if (c.Has("events")) {
    k.source = Check::Source::kEvents;
    k.name = c.RequiredString("events");
    k.robot = c.String("robot", "");
  } else {
    k.source = Check::Source::kColumn;
    k.name = c.RequiredString("column");
    if (!c.Has("stat")) c.Fail("column", "a column check needs a stat");
    const std::vector<std::string> stats(std::begin(kStatNames), std::end(kStatNames));
    k.stat = static_cast<Check::Stat>(c.Choice("stat", stats, 0));
    k.from = c.Double("from", 0.0);
    k.to = c.Double("to", k.to);
    if (!(k.to > k.from)) c.Fail("to", "the window must end after it starts (to > from)");
    if (k.stat == Check::Stat::kFirstBelow) {
      if (!c.Has("level")) c.Fail("level", "first_below needs a level");
      k.level = c.Double("level", 0.0, Tune("level").Above(0));
    }
  }
  // Over robots: `*` in the quantity's name stands for each robot of every: / any:.
  if (c.Has("every") && c.Has("any")) c.Fail("any", "a check has at most one of every, any");
  for (const char* key : {"every", "any"}) {
    if (!c.Has(key)) continue;
    k.over = std::string(key) == "every" ? Check::Over::kEvery : Check::Over::kAny;
    k.robots = c.Strings(key, {});
    if (k.robots.size() < 2 || k.robots.size() > 64)
      c.Fail(key, "names 2 ... 64 robots (a check of one robot names it in its quantity)");
    for (std::size_t i = 0; i < k.robots.size(); ++i) {
      const std::string& r = k.robots[i];
      if (r.empty() || r.size() > 64 || r.find_first_of("*{} \t\n,") != std::string::npos)
        c.Fail(key, "'" + r + "' is no robot name");
      for (std::size_t j = 0; j < i; ++j)
        if (k.robots[j] == r) c.Fail(key, "robot '" + r + "' is named twice");
    }
  }
  {
    const bool star = k.name.find('*') != std::string::npos || k.robot == "*";
    const char* key = k.source == Check::Source::kMetric   ? "metric"
                      : k.source == Check::Source::kEvents ? (k.robot.empty() ? "events" : "robot")
                                                           : "column";
    if (k.over == Check::Over::kOne && star)
      c.Fail(key, "'*' stands for each robot of every: or any:, and this check has neither");
    if (k.over != Check::Over::kOne && !star)
      c.Fail(key, std::string("a check over ") + (k.over == Check::Over::kEvery ? "every" : "any") +
                      " robot writes '*' where the robot's name goes (column: \"*.x\", robot: \"*\")");
  }
  k.ratio_to = c.String("ratio_to", "");
  if (!k.ratio_to.empty() && !IsCheckId(k.ratio_to)) c.Fail("ratio_to", "expected the id of a check");
  if (c.Has("minus")) {
    if (!k.ratio_to.empty()) c.Fail("minus", "a check has at most one of ratio_to, minus");
    k.ratio_to = c.RequiredString("minus");
    k.minus = true;
    if (!IsCheckId(k.ratio_to)) c.Fail("minus", "expected the id of a check");
  }

  const int relations =
      c.Has("less") + c.Has("greater") + c.Has("within") + c.Has("equal") + c.Has("about");
  if (relations != 1) c.Fail("id", "a check has exactly one of less, greater, within, equal, about");
  if (c.Has("less")) {
    k.relation = Check::Relation::kLess;
    ReadOperand(c, "less", k);
  } else if (c.Has("greater")) {
    k.relation = Check::Relation::kGreater;
    ReadOperand(c, "greater", k);
  } else if (c.Has("equal")) {
    k.relation = Check::Relation::kEqual;
    ReadOperand(c, "equal", k);
    k.tolerance = c.Double("tolerance", 0.0, Tune("tolerance").AtLeast(0));
  } else if (c.Has("about")) {
    k.relation = Check::Relation::kAbout;
    ReadOperand(c, "about", k);
    if (k.against.empty() && k.value == 0.0) c.Fail("about", "about a value of 0 has no relative tolerance; use equal with a tolerance");
    k.rel = c.Double("rel", 0.1, Tune("rel").Above(0).AtMost(0.5));
  } else {
    k.relation = Check::Relation::kWithin;
    const std::vector<double> r = c.Doubles("within", {}, 2);
    if (r.size() != 2 || !(r[0] <= r[1])) c.Fail("within", "expected [low, high] with low <= high");
    k.lo = r[0], k.hi = r[1];
  }
  if (k.relation != Check::Relation::kEqual && c.Has("tolerance"))
    c.Fail("tolerance", "only an equal check has a tolerance");
  if (k.relation != Check::Relation::kAbout && c.Has("rel"))
    c.Fail("rel", "only an about check has a relative tolerance (rel)");
  if (c.Has("share")) k.share = c.Double("share", 1.0, Tune("share").Above(0.5).AtMost(1));

  const YAML::Node seeds = c.Raw("seeds");
  if (!seeds.IsDefined() || seeds.IsNull())
    c.Fail("id", "state the seeds the check holds on (seeds: a number >= 5, or all)");
  if (seeds.IsScalar() && seeds.Scalar() == "all") {
    k.all_seeds = true;
  } else {
    k.seeds = c.Int("seeds", 0);
    if (k.seeds < 5 || k.seeds > 1000) c.Fail("seeds", "must be `all` or a number of seeds in [5, 1000]");
  }
  c.Finish();
  return k;
}

// A text that must hold more than blanks.
std::string NonEmpty(YamlReader& r, const std::string& key) {
  const std::string s = r.RequiredString(key);
  if (s.find_first_not_of(" \t\n") == std::string::npos) r.Fail(key, "must not be empty");
  return s;
}

constexpr int kMaxSteps = 30, kMaxScript = 20;

LessonAction ReadAction(YamlReader& a) {
  LessonAction out;
  out.label = NonEmpty(a, "label");
  out.script = a.Strings("do", {});
  if (out.script.empty() || static_cast<int>(out.script.size()) > kMaxScript)
    a.Fail("do", "an action does 1 ... " + std::to_string(kMaxScript) + " script actions");
  for (const std::string& line : out.script)
    if (line.find_first_not_of(" \t") == std::string::npos || line.find('\n') != std::string::npos)
      a.Fail("do", "a script action is one non-empty line");
  a.Finish();
  return out;
}

LessonPrediction ReadPrediction(YamlReader& p) {
  LessonPrediction out;
  out.question = NonEmpty(p, "question");
  out.options = p.Strings("options", {});
  if (out.options.size() < 2 || out.options.size() > 4)
    p.Fail("options", "a prediction offers 2 ... 4 options");
  for (std::size_t i = 0; i < out.options.size(); ++i) {
    if (out.options[i].find_first_not_of(" \t\n") == std::string::npos) p.Fail("options", "an option is empty");
    for (std::size_t j = 0; j < i; ++j)
      if (out.options[j] == out.options[i]) p.Fail("options", "option '" + out.options[i] + "' is given twice");
  }
  const std::string answer = NonEmpty(p, "answer");
  const auto it = std::find(out.options.begin(), out.options.end(), answer);
  if (it == out.options.end()) p.Fail("answer", "'" + answer + "' is not one of the options");
  out.answer = static_cast<int>(it - out.options.begin());
  out.check = NonEmpty(p, "check");
  if (p.Has("explain")) out.explain = NonEmpty(p, "explain");
  p.Finish();
  return out;
}

// A step; `ids` are the lesson's check ids.
LessonStep ReadStep(YamlReader& s, const std::set<std::string>& ids) {
  LessonStep out;
  out.line = s.node().Mark().line + 1;
  out.text = NonEmpty(s, "text");
  for (const std::string& id : CheckReferences(out.text))
    if (!ids.count(id)) s.Fail("text", "names check {" + id + "}, which is not among the lesson's checks");
  if (s.Has("check")) {
    out.check = NonEmpty(s, "check");
    if (!ids.count(out.check)) s.Fail("check", "no check '" + out.check + "' in this lesson");
  }
  if (s.Has("action")) {
    YamlReader a = s.Map("action");
    out.action = ReadAction(a);
  }
  if (s.Has("predict")) {
    YamlReader p = s.Map("predict");
    out.predict = ReadPrediction(p);
    if (!ids.count(out.predict.check)) p.Fail("check", "no check '" + out.predict.check + "' in this lesson");
    for (const std::string& id : CheckReferences(out.predict.explain))
      if (!ids.count(id)) p.Fail("explain", "names check {" + id + "}, which is not among the lesson's checks");
  }
  s.Finish();
  return out;
}

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool Contains(const std::string& s, const char* part) { return s.find(part) != std::string::npos; }

// The range of a summary.json number, from its name (the metrics' naming conventions).
LessonQuantityRange MetricRange(const std::string& name) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const std::string last = name.substr(name.rfind('.') == std::string::npos ? 0 : name.rfind('.') + 1);
  // A flag or a share: 0 ... 1, both ends reached.
  for (const char* f : {"recovered", "loop_completed", "tracking_finished", "fix_rate"})
    if (last == f) return {0.0, 1.0, true, true};
  // A count: never negative, zero is a real outcome.
  for (const char* c : {"jumps", "avoidance_entries", "accepted_outliers", "rejected_good",
                        "collisions_after_transient", "not_recovered"})
    if (last == c) return {0.0, kInf, true, true};
  if (Contains(name, "events.")) return {0.0, kInf, true, true};
  // A recovery time: zero when the error never left its band.
  if (EndsWith(last, "recover_s")) return {0.0, kInf, true, true};
  // Sizes of errors: an RMS, a maximum of |x|, a distance, a NIS / NEES (a squared norm).
  for (const char* m : {"rms", "max_abs", "nis", "nees", "position_", "linear_error",
                        "angular_error", "cross_track.max_m"})
    if (Contains(name, m)) return {0.0, kInf, false, true};
  return {};
}

}  // namespace

LessonQuantityRange QuantityRangeOf(const LessonCheck& c) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  switch (c.source) {
    case Check::Source::kEvents:
      return {0.0, kInf, true, true};
    case Check::Source::kMetric:
      return MetricRange(c.name);
    case Check::Source::kColumn:
      switch (c.stat) {
        case Check::Stat::kMaxAbs:
        case Check::Stat::kRms:
        case Check::Stat::kJitter:
          return {0.0, kInf, false, true};
        case Check::Stat::kTau:
          return {0.0, kInf, false, true};
        case Check::Stat::kFirstBelow:
          return {c.from, kInf, true, true};
        default:
          return {};
      }
  }
  return {};
}

std::vector<std::string> LessonStep::Checks() const {
  std::vector<std::string> out;
  if (!check.empty()) out.push_back(check);
  for (const std::string& id : CheckReferences(text + " " + predict.explain))
    if (std::find(out.begin(), out.end(), id) == out.end()) out.push_back(id);
  return out;
}

const char* LessonStatName(LessonCheck::Stat s) { return kStatNames[static_cast<int>(s)]; }
const char* LessonRelationName(LessonCheck::Relation r) { return kRelationNames[static_cast<int>(r)]; }

LessonCheck LessonCheck::ForRobot(const std::string& r) const {
  LessonCheck c = *this;
  c.over = Over::kOne;
  c.robots.clear();
  for (std::size_t at = c.name.find('*'); at != std::string::npos; at = c.name.find('*', at + r.size()))
    c.name.replace(at, 1, r);
  if (c.robot == "*") c.robot = r;
  return c;
}

const LessonCheck* LessonDef::Find(const std::string& id) const {
  for (const LessonCheck& c : checks)
    if (c.id == id) return &c;
  return nullptr;
}

std::vector<std::string> CheckReferences(const std::string& text) {
  std::vector<std::string> ids;
  for (std::size_t open = text.find('{'); open != std::string::npos; open = text.find('{', open + 1)) {
    const std::size_t close = text.find('}', open);
    if (close == std::string::npos) break;
    const std::string id = text.substr(open + 1, close - open - 1);
    if (IsCheckId(id)) ids.push_back(id);
  }
  return ids;
}

namespace {

// Text outside the {id} references, lower-cased (ASCII).
std::string PlainLower(const std::string& text) {
  std::string plain;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '{') {
      const std::size_t close = text.find('}', i);
      if (close != std::string::npos && IsCheckId(text.substr(i + 1, close - i - 1))) {
        i = close;
        plain += ' ';
        continue;
      }
    }
    plain += static_cast<char>(std::tolower(static_cast<unsigned char>(text[i])));
  }
  return plain;
}

bool IsWordChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || static_cast<unsigned char>(c) >= 0x80;
}

// The word at `at` starts a word (not "overshoot" inside "no_overshoot_x").
bool StartsWord(const std::string& s, std::size_t at) {
  return at == 0 || !(std::isalpha(static_cast<unsigned char>(s[at - 1])) || s[at - 1] == '_');
}

}  // namespace

bool StatesAnEffect(const std::string& text) {
  const std::string plain = PlainLower(text);
  // A number: a digit that starts a token ("2 s", "0.5", "-3", "90°"), not one inside a name
  // ("R3", "u1", "R4-R7", "formation_swarm_100").
  for (std::size_t i = 0; i < plain.size(); ++i) {
    if (!(plain[i] >= '0' && plain[i] <= '9')) continue;
    if (i > 0 && (std::isalpha(static_cast<unsigned char>(plain[i - 1])) || plain[i - 1] == '_'))
      continue;
    // "R4-R7": a digit after '-' that follows a name's digit.
    if (i > 1 && plain[i - 1] == '-' && IsWordChar(plain[i - 2])) continue;
    if (i > 0 && plain[i - 1] >= '0' && plain[i - 1] <= '9') continue;  // within a number seen
    return true;
  }
  // Comparisons and directions, as stems: "fall" is falls, fallen, falling; "grow" is grows,
  // grown; matched at the start of a word. A count of things in words ("two sensors") states
  // the setup, not a run: only the multiples compare ("twice", "four times", "threefold").
  static const char* const kStems[] = {
      "faster", "slower",  "larger",  "smaller", "bigger",  "more",     "less",     "fewer",
      "higher", "lower",   "longer",  "shorter", "grow",    "shrink",   "fall",     "drop",
      "twice",  "thrice",  "half",    "halve",   "double",  "threefold", "tenfold", "times",
      "rise",   "rises",   "worse",   "better",  "best",    "worst",    "most",     "least",
      "than",   "exceed",  "saturat", "overshoot", "within", "increase", "decrease", "reduc",
      "behind", "ahead",   "lag",     "same",    "closer",  "farther",  "further",  "nearer",
      "vanish", "decay"};
  for (const char* w : kStems) {
    const std::string stem = w;
    for (std::size_t at = plain.find(stem); at != std::string::npos; at = plain.find(stem, at + 1)) {
      if (!StartsWord(plain, at)) continue;
      const std::size_t end = at + stem.size();
      // Whole words: "less", not "lesson"; "most", not "mostly"; "lag" and lags, lagged, lagging.
      const bool whole = stem == "most" || stem == "less" || stem == "more" || stem == "same" ||
                         stem == "lag" || stem == "than";
      if (whole && end < plain.size() && std::isalpha(static_cast<unsigned char>(plain[end]))) {
        if (!(stem == "lag" && plain.compare(end, 1, "s") == 0) &&
            !(stem == "lag" && plain.compare(end, 3, "ged") == 0) &&
            !(stem == "lag" && plain.compare(end, 4, "ging") == 0))
          continue;
      }
      return true;
    }
  }
  return false;
}

std::vector<std::string> SplitSentences(const std::string& text) {
  std::vector<std::string> out;
  std::string cur;
  auto push = [&] {
    const std::size_t a = cur.find_first_not_of(" \t\n");
    if (a != std::string::npos) out.push_back(cur.substr(a, cur.find_last_not_of(" \t\n") + 1 - a));
    cur.clear();
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    cur += text[i];
    const char c = text[i];
    if (c != '.' && c != '!' && c != '?') continue;
    const bool end = i + 1 == text.size() || text[i + 1] == ' ' || text[i + 1] == '\n' || text[i + 1] == '\t';
    if (!end) continue;
    // "e.g." and "i.e." and "et al." do not end a sentence.
    const std::string low = PlainLower(cur);
    bool abbrev = false;
    for (const char* a : {"e.g.", "i.e.", "et al.", "cf.", "vs."})
      abbrev = abbrev || (low.size() >= std::strlen(a) && low.compare(low.size() - std::strlen(a), std::strlen(a), a) == 0);
    if (abbrev) continue;
    // A following `{id}` belongs to this sentence ("... doubles. {tau_half}" is rare; keep it).
    push();
  }
  push();
  return out;
}

const std::vector<std::string>& LessonInstructionVerbs() {
  static const std::vector<std::string> kVerbs = {
      "set",   "move",  "put",    "lower", "raise",   "halve", "double", "stretch", "restore",
      "load",  "press", "choose", "pick",  "switch",  "turn",  "drag",   "pin",     "reset",
      "play",  "open",  "watch",  "look",  "predict", "under", "give",   "add",     "remove",
      "try",   "make",  "undo",   "run",   "step",    "replace"};
  return kVerbs;
}

std::string ClaimPart(const std::string& sentence) {
  const std::size_t a = sentence.find_first_not_of(" \t\n");
  if (a == std::string::npos) return "";
  std::size_t b = a;
  while (b < sentence.size() && std::isalpha(static_cast<unsigned char>(sentence[b]))) ++b;
  std::string first = sentence.substr(a, b - a);
  for (char& c : first) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const auto& verbs = LessonInstructionVerbs();
  if (std::find(verbs.begin(), verbs.end(), first) == verbs.end()) return sentence;
  const std::size_t colon = sentence.find(':');
  return colon == std::string::npos ? std::string() : sentence.substr(colon + 1);
}

std::vector<UnbackedSentence> SentencesWithoutCheck(const LessonDef& l) {
  std::vector<UnbackedSentence> out;
  auto scan = [&](const std::string& where, int line, const std::string& paragraph) {
    for (const std::string& s : SplitSentences(paragraph))
      if (CheckReferences(s).empty() && StatesAnEffect(ClaimPart(s))) out.push_back({where, line, s});
  };
  scan("goal", 0, l.goal);
  for (std::size_t i = 0; i < l.steps.size(); ++i) {
    const LessonStep& s = l.steps[i];
    scan("step " + std::to_string(i + 1), s.line, s.text);
    if (!s.predict.explain.empty())
      scan("step " + std::to_string(i + 1) + "'s explanation", s.line, s.predict.explain);
  }
  return out;
}

bool ClaimsASeedEffect(const std::string& sentence) {
  const std::string p = PlainLower(sentence);
  for (const char* w : {"seed", "varies", "vary ", "varying", "depends on the noise",
                        "depend on the noise", "on some seeds", "noise draw", "from run to run"})
    if (p.find(w) != std::string::npos) return true;
  // "in 27 of 30", "on 24 of the first 30": a count over runs.
  for (std::size_t at = p.find(" of "); at != std::string::npos; at = p.find(" of ", at + 1)) {
    std::size_t b = at;
    while (b > 0 && p[b - 1] >= '0' && p[b - 1] <= '9') --b;
    if (b == at) continue;
    std::size_t e = at + 4;
    if (p.compare(e, 10, "the first ") == 0) e += 10;
    if (e < p.size() && p[e] >= '0' && p[e] <= '9') return true;
  }
  return false;
}

std::vector<std::pair<std::string, std::string>> ChecksClaimingASeedEffect(const LessonDef& l) {
  std::vector<std::pair<std::string, std::string>> out;
  auto add = [&](const std::string& id, const std::string& why) {
    for (const auto& [have, _] : out)
      if (have == id) return;
    out.emplace_back(id, why);
  };
  std::vector<std::string> paragraphs = {l.goal};
  for (const LessonStep& s : l.steps) {
    paragraphs.push_back(s.text);
    paragraphs.push_back(s.predict.explain);
  }
  for (const std::string& p : paragraphs)
    for (const std::string& s : SplitSentences(p))
      if (ClaimsASeedEffect(s))
        for (const std::string& id : CheckReferences(s)) add(id, s);
  for (const LessonCheck& c : l.checks)
    if (c.share < 1) add(c.id, "share: " + FormatSignificant(c.share));
  return out;
}

LessonDef ReadLesson(YamlReader& b) {
  LessonDef l;
  l.present = true;
  l.title = NonEmpty(b, "title");
  l.goal = NonEmpty(b, "goal");
  l.equations = b.Strings("equations", {});
  for (const std::string& e : l.equations)
    if (e.find_first_not_of(" \t\n") == std::string::npos) b.Fail("equations", "an equation is empty");
  std::set<std::string> ids;
  for (YamlReader& c : b.MapList("checks")) {
    l.checks.push_back(ReadCheck(c));
    if (!ids.insert(l.checks.back().id).second)
      c.Fail("id", "check '" + l.checks.back().id + "' is declared twice");
  }
  std::vector<YamlReader> items = b.MapList("checks");
  for (std::size_t i = 0; i < l.checks.size(); ++i) {
    const LessonCheck& k = l.checks[i];
    for (const std::string* other : {&k.against, &k.ratio_to}) {
      if (other->empty()) continue;
      if (!ids.count(*other)) items[i].Fail(other == &k.ratio_to ? (k.minus ? "minus" : "ratio_to") : LessonRelationName(k.relation),
                                            "no check '" + *other + "' in this lesson");
      if (*other == k.id) items[i].Fail("id", "a check cannot refer to itself");
    }
  }
  // A check over robots pairs robot by robot with the checks it refers to over robots: the
  // same robots. A check of one quantity has one value to compare; it cannot refer to one over
  // robots (which of them?).
  for (std::size_t i = 0; i < l.checks.size(); ++i) {
    const LessonCheck& k = l.checks[i];
    for (const std::string* other : {&k.against, &k.ratio_to}) {
      const LessonCheck* o = other->empty() ? nullptr : l.Find(*other);
      if (o == nullptr || o->over == Check::Over::kOne) continue;
      const char* key = other == &k.ratio_to ? (k.minus ? "minus" : "ratio_to") : LessonRelationName(k.relation);
      if (k.over == Check::Over::kOne)
        items[i].Fail(key, "check '" + o->id + "' is measured per robot; only a check over the same robots (every: or any:) can refer to it");
      if (o->robots != k.robots)
        items[i].Fail(key, "check '" + o->id + "' is over other robots; a check over robots refers to one over the same robots, in the same order");
    }
  }
  // A check that cannot fail: a bound at or beyond its quantity's range.
  std::function<LessonQuantityRange(const LessonCheck&, int)> range = [&](const LessonCheck& k,
                                                                         int depth) {
    LessonQuantityRange r = QuantityRangeOf(k);
    if (k.ratio_to.empty()) return r;
    if (k.minus) return LessonQuantityRange{};
    const LessonCheck* d = l.Find(k.ratio_to);
    const LessonQuantityRange dr = d == nullptr || depth > 8 ? LessonQuantityRange{} : range(*d, depth + 1);
    // A ratio of two non-negative quantities is non-negative (and 0 only where the numerator is).
    if (r.lo >= 0 && dr.lo >= 0) return LessonQuantityRange{0.0, std::numeric_limits<double>::infinity(), r.lo_reached && r.lo == 0, true};
    return LessonQuantityRange{};
  };
  for (std::size_t i = 0; i < l.checks.size(); ++i) {
    const LessonCheck& k = l.checks[i];
    const LessonQuantityRange r = range(k, 0);
    auto at_lo = [&](double b) { return b < r.lo || (b == r.lo && !r.lo_reached); };
    auto at_hi = [&](double b) { return b > r.hi || (b == r.hi && !r.hi_reached); };
    const std::string span = "[" + FormatRangeEnd(r.lo) + ", " + FormatRangeEnd(r.hi) + "]";
    const std::string why = " cannot fail: its quantity lies in " + span;
    if (!k.against.empty()) continue;
    if (k.relation == Check::Relation::kGreater && at_lo(k.value))
      items[i].Fail("greater", "check '" + k.id + "' (greater: " + FormatRangeEnd(k.value) + ")" + why +
                                   (r.lo_reached || k.value < r.lo ? "" : " and never equals " + FormatRangeEnd(r.lo)));
    if (k.relation == Check::Relation::kLess && at_hi(k.value))
      items[i].Fail("less", "check '" + k.id + "' (less: " + FormatRangeEnd(k.value) + ")" + why +
                                (r.hi_reached || k.value > r.hi ? "" : " and never equals " + FormatRangeEnd(r.hi)));
    if ((k.relation == Check::Relation::kGreater && k.value >= r.hi) ||
        (k.relation == Check::Relation::kLess && k.value <= r.lo))
      items[i].Fail(LessonRelationName(k.relation),
                    "check '" + k.id + "' can never hold: its quantity lies in " + span);
    if (k.relation == Check::Relation::kWithin && k.lo <= r.lo && k.hi >= r.hi)
      items[i].Fail("within", "check '" + k.id + "' cannot fail: [" + FormatRangeEnd(k.lo) + ", " +
                                  FormatRangeEnd(k.hi) + "] covers its quantity's range " + span);
  }
  for (const std::string& id : CheckReferences(l.goal))
    if (!ids.count(id)) b.Fail("goal", "names check {" + id + "}, which is not among the lesson's checks");
  if (!b.Has("steps")) b.Fail("steps", "a lesson is a list of steps (steps: [{text: ...}, ...])");
  for (YamlReader& s : b.MapList("steps")) l.steps.push_back(ReadStep(s, ids));
  if (l.steps.empty() || static_cast<int>(l.steps.size()) > kMaxSteps)
    b.Fail("steps", "a lesson has 1 ... " + std::to_string(kMaxSteps) + " steps");
  b.Finish();
  return l;
}

}  // namespace formsim::sim
