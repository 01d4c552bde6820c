#include "sim/session/run_log.hpp"

namespace formsim::sim {

RunLog RunLog::Before(long step) const {
  RunLog out;
  out.base = base;
  for (const RunChange& c : changes)
    if (c.step < step) out.changes.push_back(c);
  return out;
}

std::vector<Override> RunLog::Edits() const {
  std::vector<Override> out;
  for (const RunChange& c : changes)
    if (c.kind == RunChange::Kind::kEdits) out.insert(out.end(), c.edits.begin(), c.edits.end());
  return out;
}

std::string ApplyRunChange(Experiment& exp, const RunChange& change, const ParsedScenario* parsed) {
  switch (change.kind) {
    case RunChange::Kind::kEdits:
      if (parsed == nullptr) return "no configuration for the edits";
      try {
        exp.Retune(*parsed->config);
      } catch (const std::exception& e) {
        return std::string("could not apply: ") + e.what();
      }
      for (Override o : change.edits) {
        o.step = exp.steps();
        exp.NoteOverride(o);
      }
      return "";
    case RunChange::Kind::kMove:
      return exp.Move(change.name, {change.x, change.y});
    case RunChange::Kind::kAction: {
      const std::string err = exp.RunAction(change.name);
      if (err.empty()) exp.NoteOverride({"action", change.name, change.origin, exp.steps()});
      return err;
    }
  }
  return "";
}

RunReplay::RunReplay(ScenarioSource source, RunLog log,
                     const std::function<void(Experiment&)>& setup)
    : source_(std::move(source)), log_(std::move(log)) {
  parsed_ = ParseScenario(source_, log_.base);
  exp_ = BuildExperiment(parsed_);
  if (setup) setup(*exp_);
  edits_so_far_ = log_.base;
}

void RunReplay::ApplyDue(long step) {
  while (next_ < log_.changes.size() && log_.changes[next_].step <= step) {
    const RunChange& c = log_.changes[next_++];
    if (c.step < step) continue;  // a change of a step already passed (a malformed log)
    const ParsedScenario* parsed = nullptr;
    ParsedScenario next;
    if (c.kind == RunChange::Kind::kEdits) {
      std::vector<Override> all = edits_so_far_;
      all.insert(all.end(), c.edits.begin(), c.edits.end());
      next = ParseScenario(source_, all);
      parsed = &next;
    }
    // The live run applied these successfully (failures are not logged), so they apply here.
    (void)ApplyRunChange(*exp_, c, parsed);
    if (parsed != nullptr) {
      edits_so_far_.insert(edits_so_far_.end(), c.edits.begin(), c.edits.end());
      parsed_ = std::move(next);
    }
  }
}

bool RunReplay::AdvanceTo(long step, bool changes_at_step, const std::function<bool()>& stop) {
  long n = 0;
  while (exp_->steps() < step && !exp_->finished()) {
    ApplyDue(exp_->steps());
    exp_->Step();
    if ((++n & 15) == 0 && stop && stop()) return exp_->steps() >= step || exp_->finished();
  }
  if (changes_at_step && exp_->steps() == step) ApplyDue(step);
  return true;
}

}  // namespace formsim::sim
