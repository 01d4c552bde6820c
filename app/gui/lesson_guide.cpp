#include "app/gui/lesson_guide.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "app/gui/ui.hpp"
#include "sim/core/number_format.hpp"

namespace formsim::app {
namespace {

// A value as compared between edits: numbers by value ("0.50" is "0.5"), the rest as text.
std::string Canonical(const std::string& v) {
  double x = 0;
  return sim::ParseFiniteDouble(v, &x) ? sim::FormatDouble(x) : v;
}

std::string Letter(int option) { return std::string(1, static_cast<char>('A' + option - 1)); }

// "the run reaches t = 3 s" or "the run has ended", for a check not measured yet.
std::string WhenReady(const sim::LessonDef& l, const sim::LessonCheck& c) {
  const double t = sim::CheckNeedsTime(l, c);
  return std::isfinite(t) ? "once the run reaches t = " + sim::FormatSignificant(t, 4) + " s"
                          : "once the run has ended";
}

}  // namespace

sim::RunEdits CurrentRunEdits(const sim::Session& session) {
  const sim::RunLog log = session.run_log();
  sim::RunEdits r;
  for (const sim::Override& o : log.base) {
    if (o.key == "seed") continue;
    // An edit back to the file's value is the lesson's own run again (a --set stays an edit).
    if (o.origin != "--set" && Canonical(o.value) == Canonical(session.LoadedValue(o.key)))
      r.edits.erase(o.key);
    else
      r.edits[o.key] = o.value;
  }
  r.changed_while_running = !log.changes.empty();
  return r;
}

std::string LessonGuide::Inactive() const {
  const sim::LessonDef& l = ctx_.session().lesson();
  if (!l.present) return "this scenario is no lesson (open one: lesson NAME, or Help/Lessons)";
  return l.steps.empty() ? "this lesson has no steps" : "";
}

std::string LessonGuide::Name() const {
  return std::filesystem::path(ctx_.session().file()).stem().string();
}

int LessonGuide::Steps() const {
  return Inactive().empty() ? static_cast<int>(ctx_.session().lesson().steps.size()) : 0;
}

int LessonGuide::Step() const {
  const int n = Steps();
  if (n == 0) return 0;
  const auto& all = (*ctx_.state).settings.lessons;
  const auto it = all.find(Name());
  return it == all.end() ? 1 : std::min(std::max(it->second.step, 1), n);
}

const sim::LessonStep* LessonGuide::Current() const {
  const int s = Step();
  return s == 0 ? nullptr : &ctx_.session().lesson().steps[static_cast<std::size_t>(s - 1)];
}

LessonProgress LessonGuide::Progress() const {
  const auto& all = (*ctx_.state).settings.lessons;
  const auto it = all.find(Name());
  return it == all.end() ? LessonProgress{} : it->second;
}

LessonProgress& LessonGuide::Mutable() { return (*ctx_.state).settings.lessons[Name()]; }

void LessonGuide::Save() {
  const std::string err = SaveUiSettings((*ctx_.state).settings);
  if (!err.empty()) ctx_.SetStatus("lesson progress not kept: " + err, true);
}

std::string LessonGuide::GoTo(int n) {
  if (const std::string why = Inactive(); !why.empty()) return why;
  const int steps = Steps();
  if (n < 1 || n > steps)
    return "step " + std::to_string(n) + " is out of range: this lesson has steps 1 ... " +
           std::to_string(steps);
  Mutable().step = n;
  Save();
  (*ctx_.state).select_tab = "lesson";
  ctx_.SetStatus("Lesson step " + std::to_string(n) + " of " + std::to_string(steps));
  return "";
}

std::string LessonGuide::Next() {
  if (const std::string why = Inactive(); !why.empty()) return why;
  const int s = Step();
  if (s >= Steps()) return "this is the lesson's last step";
  Mutable().done.insert(s);
  return GoTo(s + 1);
}

std::string LessonGuide::ActionBlocked() const {
  if (const std::string why = Inactive(); !why.empty()) return why;
  const int s = Step();
  const sim::LessonStep& step = *Current();
  if (step.action.label.empty()) return "step " + std::to_string(s) + " has no action";
  if (!step.predict.question.empty() && !Progress().predicted.count(s))
    return "predict first: choose an option of step " + std::to_string(s) + " (lesson-predict K)";
  return "";
}

std::string LessonGuide::RunAction() {
  if (const std::string why = ActionBlocked(); !why.empty()) return why;
  const int s = Step();
  const sim::LessonStep step = *Current();  // a copy: an action may replace the session
  const std::string name = Name();
  for (const std::string& line : step.action.script) {
    // Through the command table, as a script line: recorded and undoable like any edit.
    const std::string err = ctx_.run(line);
    if (!err.empty()) {
      const std::string why = "step " + std::to_string(s) + "'s action '" + line + "': " + err;
      ctx_.SetStatus(why, true);
      return why;
    }
  }
  (*ctx_.state).settings.lessons[name].done.insert(s);
  Save();
  ctx_.SetStatus("Step " + std::to_string(s) + ": " + step.action.label);
  return "";
}

std::string LessonGuide::Predict(int k) {
  if (const std::string why = Inactive(); !why.empty()) return why;
  const int s = Step();
  const sim::LessonPrediction& p = Current()->predict;
  if (p.question.empty()) return "step " + std::to_string(s) + " asks for no prediction";
  const int n = static_cast<int>(p.options.size());
  if (k < 1 || k > n)
    return "option " + std::to_string(k) + " is out of range: step " + std::to_string(s) +
           " offers options 1 ... " + std::to_string(n);
  LessonProgress& prog = Mutable();
  prog.predicted[s] = k;
  prog.done.insert(s);
  Save();
  ctx_.SetStatus("You predicted " + Letter(k) + ": " + p.options[static_cast<std::size_t>(k - 1)]);
  return "";
}

sim::LiveCheck LessonGuide::Live(const std::string& id) {
  const sim::Session& session = ctx_.session();
  const sim::Experiment& exp = session.exp();
  const sim::RunLog log = session.run_log();
  if (run_exp_ != &exp || run_id_ != session.run_id() || run_changes_ != log.changes.size()) {
    run_exp_ = &exp;
    run_id_ = session.run_id();
    run_changes_ = log.changes.size();
    live_.clear();
  }
  if (const auto it = live_.find(id); it != live_.end()) return it->second;
  const sim::LessonDef& l = session.lesson();
  const sim::LessonCheck* c = l.Find(id);
  if (c == nullptr) return {true, 0.0, false, "no check '" + id + "' in this lesson"};
  const sim::LiveCheck r = sim::MeasureOnRun(l, *c, exp, CurrentRunEdits(session));
  // Measured once the run has reached what the check needs; later steps cannot change it.
  if (r.ready) live_[id] = r;
  return r;
}

std::string LessonGuide::Render(const std::string& paragraph) {
  return sim::RenderLessonParagraph(paragraph, [this](const std::string& id) {
    const sim::LiveCheck r = Live(id);
    sim::ShownCheck s;
    s.measured = r.ready && r.error.empty();
    s.value = r.value;
    s.holds = r.holds;
    s.robot = r.robot;
    const sim::LessonCheck* c = ctx_.session().lesson().Find(id);
    s.some_seeds = c != nullptr && c->share < 1;
    return s;
  });
}

std::string LessonGuide::SeeLine(const std::string& id) {
  const sim::LessonDef& l = ctx_.session().lesson();
  const sim::LessonCheck* c = l.Find(id);
  if (c == nullptr) return id + ": no such check";
  const std::string head = id + "  " + sim::LessonRelationText(*c) + ":  ";
  const sim::LiveCheck r = Live(id);
  if (!r.ready) return head + "not yet (measured " + WhenReady(l, *c) + ")";
  if (!r.error.empty()) return head + r.error;
  return head + sim::FormatSignificant(r.value, 4) +
         (r.holds ? "  √ holds" : "  not yet (does not hold on this run)");
}

bool LessonGuide::Judged() {
  const sim::LessonStep* step = Current();
  if (step == nullptr || step->predict.question.empty()) return false;
  if (!Progress().predicted.count(Step())) return false;
  const sim::LiveCheck r = Live(step->predict.check);
  return r.ready && r.error.empty();
}

std::string LessonGuide::Verdict() {
  const sim::LessonStep* step = Current();
  if (step == nullptr || step->predict.question.empty()) return "";
  const sim::LessonPrediction p = step->predict;
  const auto prog = Progress();
  const auto it = prog.predicted.find(Step());
  if (it == prog.predicted.end()) return "Choose an option, then run.";
  const int k = std::min(it->second, static_cast<int>(p.options.size()));
  const std::string mine = "You predicted " + Letter(k);
  const sim::LessonCheck* c = ctx_.session().lesson().Find(p.check);
  if (c == nullptr) return mine + ".";
  const sim::LiveCheck r = Live(p.check);
  if (!r.ready)
    return mine + ". The run shows it " + WhenReady(ctx_.session().lesson(), *c) + ": play it.";
  if (!r.error.empty()) return mine + ". Not on this run: " + r.error;
  const bool right = k - 1 == p.answer;
  std::string out = mine + (right ? " — right" : " — not quite (the answer is " + Letter(p.answer + 1) + ")");
  out += ": " + p.check + " measured " + sim::FormatSignificant(r.value, 4) + ", " +
         sim::LessonRelationText(*c);
  if (!r.holds) out += " (on this run the check does not hold)";
  return out;
}

}  // namespace formsim::app
