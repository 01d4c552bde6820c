#include "sim/scenario/lesson.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <set>

namespace formsim::sim {
namespace {

using Check = LessonCheck;

constexpr const char* kStatNames[] = {"max_abs", "max",    "min",         "mean", "rms",
                                      "jitter",  "first_below", "tau", "final"};
constexpr const char* kRelationNames[] = {"less", "greater", "within", "equal"};

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
  k.ratio_to = c.String("ratio_to", "");
  if (!k.ratio_to.empty() && !IsCheckId(k.ratio_to)) c.Fail("ratio_to", "expected the id of a check");

  const int relations = c.Has("less") + c.Has("greater") + c.Has("within") + c.Has("equal");
  if (relations != 1) c.Fail("id", "a check has exactly one of less, greater, within, equal");
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
  } else {
    k.relation = Check::Relation::kWithin;
    const std::vector<double> r = c.Doubles("within", {}, 2);
    if (r.size() != 2 || !(r[0] <= r[1])) c.Fail("within", "expected [low, high] with low <= high");
    k.lo = r[0], k.hi = r[1];
  }
  if (k.relation != Check::Relation::kEqual && c.Has("tolerance"))
    c.Fail("tolerance", "only an equal check has a tolerance");

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

}  // namespace

std::vector<std::string> LessonStep::Checks() const {
  std::vector<std::string> out;
  if (!check.empty()) out.push_back(check);
  for (const std::string& id : CheckReferences(text + " " + predict.explain))
    if (std::find(out.begin(), out.end(), id) == out.end()) out.push_back(id);
  return out;
}

const char* LessonStatName(LessonCheck::Stat s) { return kStatNames[static_cast<int>(s)]; }
const char* LessonRelationName(LessonCheck::Relation r) { return kRelationNames[static_cast<int>(r)]; }

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

bool StatesAnEffect(const std::string& text) {
  // Text outside the {id} references, lower-cased (ASCII).
  std::string plain;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '{') {
      const std::size_t close = text.find('}', i);
      if (close != std::string::npos) {
        i = close;
        continue;
      }
    }
    plain += static_cast<char>(std::tolower(static_cast<unsigned char>(text[i])));
  }
  for (char c : plain)
    if (c >= '0' && c <= '9') return true;
  static const char* const kWords[] = {
      "faster", "slower", "larger",  "smaller", "bigger", "more ",  " less",  "fewer",
      "higher", "lower",  "longer",  "shorter", "grows",  "shrinks", "falls", "drops",
      "twice",  "half",   "halves",  "doubles", "rises",  "worse",  "better", "than",
      "exceed", "saturat", "overshoot", "within"};
  for (const char* w : kWords)
    if (plain.find(w) != std::string::npos) return true;
  return false;
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
      if (!ids.count(*other)) items[i].Fail(other == &k.ratio_to ? "ratio_to" : LessonRelationName(k.relation),
                                            "no check '" + *other + "' in this lesson");
      if (*other == k.id) items[i].Fail("id", "a check cannot refer to itself");
    }
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
