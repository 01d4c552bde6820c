#include "sim/scenario/lesson.hpp"

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

}  // namespace

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
  auto text = [&](const char* key) {
    const std::string s = b.RequiredString(key);
    if (s.find_first_not_of(" \t\n") == std::string::npos) b.Fail(key, "must not be empty");
    return s;
  };
  l.title = text("title");
  l.goal = text("goal");
  l.watch = text("watch");
  l.try_next = text("try_next");
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
  for (const char* key : {"goal", "watch", "try_next"}) {
    const std::string& p = key[0] == 'g' ? l.goal : key[0] == 'w' ? l.watch : l.try_next;
    for (const std::string& id : CheckReferences(p))
      if (!ids.count(id))
        b.Fail(key, "names check {" + id + "}, which is not among the lesson's checks");
  }
  b.Finish();
  return l;
}

}  // namespace formsim::sim
