#include "sim/session/session.hpp"

#include <filesystem>
#include <iterator>
#include <stdexcept>

#include "sim/core/number_format.hpp"
#include "sim/core/run_output.hpp"
#include "sim/scenario/scenario_files.hpp"
#include "sim/scenario/scenario_save.hpp"
#include "sim/core/structure_editing.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {

Session::Session(const std::string& file, std::vector<Override> cli_overrides)
    : Session(ScenarioSource::FromFile(file), std::move(cli_overrides)) {}

Session::Session(ScenarioSource source, std::vector<Override> cli_overrides)
    : source_(std::move(source)), disk_file_(source_.file()), cli_(std::move(cli_overrides)), base_(cli_) {
  applied_ = ParseScenario(source_, base_);
  loaded_ = applied_.params;
  exp_ = BuildExperiment(applied_);
}

Session::Session(const std::string& file, const std::vector<std::string>& sets, long long seed)
    : Session(file, CliOverrides(sets, seed)) {}

void Session::SetRunSetup(std::function<void(Experiment&)> setup) {
  run_setup_ = std::move(setup);
  if (run_setup_) run_setup_(*exp_);
}

void Session::Reject(const std::string& key, const std::string& why) {
  rejected_.push_back(Sprintf("t=%.2f s ", exp_->time()) + key + ": " + why);
  if (rejected_.size() > 50) rejected_.erase(rejected_.begin());
  refusals_[key] = why;
}

void Session::Notify(SessionEvent e, long step) const {
  if (!observer_) return;
  e.step = step >= 0 ? step : exp_->steps();
  observer_(e);
}

std::string Session::refusal(const std::string& key) const {
  const auto it = refusals_.find(key);
  return it == refusals_.end() ? "" : it->second;
}

std::vector<Override> Session::All(bool with_reset_edits) const {
  std::vector<Override> all = base_;
  all.insert(all.end(), run_edits_.begin(), run_edits_.end());
  all.insert(all.end(), queued_.begin(), queued_.end());
  if (with_reset_edits) all.insert(all.end(), reset_edits_.begin(), reset_edits_.end());
  return all;
}

std::vector<Override> Session::EffectiveOverrides() const {
  return LastValuePerKey(All(true));
}

std::string Session::EffectiveValue(const std::string& key) const {
  // The order of All(true): the edits waiting for a reset come last.
  for (auto it = reset_edits_.rbegin(); it != reset_edits_.rend(); ++it)
    if (it->key == key) return it->value;
  for (auto it = queued_.rbegin(); it != queued_.rend(); ++it)
    if (it->key == key) return it->value;
  const Param* p = applied_.params.Find(key);
  return p == nullptr ? "" : p->Text();
}

std::string Session::LoadedValue(const std::string& key) const {
  const Param* p = loaded_.Find(key);
  return p == nullptr ? "" : p->Text();
}

bool Session::IsEdited(const std::string& key) const {
  const Param* p = loaded_.Find(key);
  return p != nullptr && EffectiveValue(key) != p->Text();
}

std::map<std::string, std::string> Session::waiting_for_reset() const {
  std::map<std::string, std::string> out;
  for (const Override& o : reset_edits_) out[o.key] = o.value;
  return out;
}

std::string Session::Edit(const std::string& key, const std::string& value,
                          const std::string& origin, bool continues_gesture) {
  const Param* p = applied_.params.Find(key);
  if (p == nullptr) {
    const std::string why = "unknown parameter (not a tunable of this scenario)";
    Reject(key, why);
    return why;
  }
  std::string canonical;
  if (std::string why = p->Parse(value, &canonical); !why.empty()) {
    why = origin + " " + key + "=" + value + ": " + why;
    Reject(key, why);
    return why;
  }
  const std::string before = EffectiveValue(key);
  const Override edit{key, canonical, origin, -1};
  // The scenario as the next reset would read it must stay valid (cross-field rules included).
  std::vector<Override> all = All(true);
  all.push_back(edit);
  try {
    (void)ParseScenario(source_, all);
  } catch (const std::exception& e) {
    Reject(key, e.what());
    return e.what();
  }
  bool live = p->tune.live;
  if (live) {
    std::vector<Override> now = All(false);
    now.push_back(edit);
    try {
      queued_parse_ = ParseScenario(source_, now);
      queued_.push_back(edit);
    } catch (const std::exception&) {
      live = false;  // valid only together with edits that wait for a reset: wait too
    }
  }
  if (!live) {
    bool replaced = false;
    for (Override& o : reset_edits_)
      if (o.key == key) {
        o = edit;
        replaced = true;
      }
    if (!replaced) reset_edits_.push_back(edit);
  }
  ++accepted_;
  refusals_.erase(key);
  // Undo steps: undo and redo move between the two stacks themselves.
  if (origin != "undo" && origin != "redo") {
    // A gesture may edit a few keys together (a slot dragged edits l_des and φ_des): it
    // continues the latest undo step of the same key among the last few.
    auto same = undo_.end();
    if (continues_gesture)
      for (auto it = undo_.rbegin(); it != undo_.rend() && it - undo_.rbegin() < 4; ++it)
        if (!it->structure && it->key == key) {
          same = std::prev(it.base());
          break;
        }
    if (same != undo_.end()) {
      same->after = canonical;
      if (same->after == same->before) undo_.erase(same);  // dragged back
    } else if (before != canonical) {
      undo_.push_back({key, before, canonical});
      if (undo_.size() > 500) undo_.erase(undo_.begin());
    }
    redo_.clear();
  }
  SessionEvent e;
  e.kind = SessionEvent::Kind::kEdit;
  e.key = key;
  e.value = canonical;
  e.origin = origin;
  Notify(e);
  return "";
}

std::string Session::RestructureTo(const std::string& text, const std::string& origin) {
  std::string placed;
  try {
    const auto* editing = exp_->As<StructureEditing>();
    if (editing == nullptr)
      throw std::runtime_error("this kind of scenario offers no structural changes");
    placed = editing->PlacedText(text);  // the robots stay where they are now
  } catch (const std::exception& e) {
    return origin + " refused: " + e.what();
  }
  if (std::string err = AdoptStructure(placed, "", origin); !err.empty())
    return origin + " refused: " + err;
  return "";
}

std::string Session::Undo() {
  if (undo_.empty()) return "nothing to undo";
  const UndoStep u = undo_.back();
  if (u.structure) {
    if (std::string err = RestructureTo(u.before, "undo"); !err.empty()) return err;
    undo_.pop_back();
    redo_.push_back(u);
    return "";
  }
  if (std::string err = Edit(u.key, u.before, "undo"); !err.empty()) return "undo refused: " + err;
  undo_.pop_back();
  redo_.push_back(u);
  return "";
}

std::string Session::Redo() {
  if (redo_.empty()) return "nothing to redo";
  const UndoStep u = redo_.back();
  if (u.structure) {
    if (std::string err = RestructureTo(u.after, "redo"); !err.empty()) return err;
    redo_.pop_back();
    undo_.push_back(u);
    return "";
  }
  if (std::string err = Edit(u.key, u.after, "redo"); !err.empty()) return "redo refused: " + err;
  redo_.pop_back();
  undo_.push_back(u);
  return "";
}

std::string Session::UndoText() const {
  if (undo_.empty()) return "";
  if (undo_.back().structure) return "formation: " + undo_.back().key;
  return undo_.back().key + " " + undo_.back().after + " -> " + undo_.back().before;
}

std::string Session::RedoText() const {
  if (redo_.empty()) return "";
  if (redo_.back().structure) return "formation: " + redo_.back().key;
  return redo_.back().key + " " + redo_.back().before + " -> " + redo_.back().after;
}

void Session::Move(const std::string& name, double x, double y) {
  moves_.push_back({name, x, y});
  SessionEvent e;
  e.kind = SessionEvent::Kind::kMove;
  e.key = name;
  e.x = x;
  e.y = y;
  Notify(e);
}

std::string Session::Action(const std::string& id, const std::string& origin) {
  for (const ActionSpec& a : exp_->Actions())
    if (a.id == id) {
      actions_.push_back({"action", id, origin, -1});
      SessionEvent e;
      e.kind = SessionEvent::Kind::kAction;
      e.key = id;
      e.origin = origin;
      Notify(e);
      return "";
    }
  const std::string why = "no action '" + id + "' in this scenario";
  Reject("action", why);
  return why;
}

void Session::ApplyPending() {
  if (!has_pending()) return;
  SessionEvent apply;
  apply.kind = SessionEvent::Kind::kApply;
  Notify(apply);
  // Each change goes through ApplyRunChange, as a replay of the run log applies it.
  if (!queued_.empty() && queued_parse_) {
    RunChange c;
    c.kind = RunChange::Kind::kEdits;
    c.step = exp_->steps();
    c.edits = queued_;
    for (Override& o : c.edits) o.step = c.step;
    const std::string err = ApplyRunChange(*exp_, c, &*queued_parse_);
    if (err.empty()) {
      applied_ = std::move(*queued_parse_);
      run_edits_.insert(run_edits_.end(), c.edits.begin(), c.edits.end());
      changes_.push_back(std::move(c));
    } else {
      for (const Override& o : queued_) Reject(o.key, err);
    }
  }
  queued_.clear();
  queued_parse_.reset();
  for (const MoveRequest& m : moves_) {
    RunChange c;
    c.kind = RunChange::Kind::kMove;
    c.step = exp_->steps();
    c.name = m.name;
    c.x = m.x;
    c.y = m.y;
    const std::string err = ApplyRunChange(*exp_, c, nullptr);
    if (!err.empty())
      Reject("move", err);
    else
      changes_.push_back(std::move(c));
  }
  moves_.clear();
  for (const Override& a : actions_) {
    RunChange c;
    c.kind = RunChange::Kind::kAction;
    c.step = exp_->steps();
    c.name = a.value;
    c.origin = a.origin;
    const std::string err = ApplyRunChange(*exp_, c, nullptr);
    if (!err.empty())
      Reject("action " + a.value, err);
    else
      changes_.push_back(std::move(c));
  }
  actions_.clear();
}

void Session::Step() {
  ApplyPending();
  exp_->Step();
}

std::string Session::Reset(std::optional<std::uint64_t> seed) {
  const long from = exp_->steps();
  std::vector<Override> all = All(true);
  if (seed) all.push_back({"seed", std::to_string(*seed), "reset with seed", -1});
  all = LastValuePerKey(all);
  try {
    ParsedScenario parsed = ParseScenario(source_, all);
    std::unique_ptr<Experiment> exp = BuildExperiment(parsed);
    if (run_setup_) {
      exp_->mutable_recorder().AbandonStream();  // the old run's file goes before the new opens
      run_setup_(*exp);
    }
    applied_ = std::move(parsed);
    exp_ = std::move(exp);
  } catch (const std::exception& e) {
    return std::string("reset failed, the run goes on unchanged: ") + e.what();
  }
  base_ = std::move(all);
  reset_edits_.clear();
  StartRun();
  SessionEvent e;
  e.kind = SessionEvent::Kind::kReset;
  e.has_seed = seed.has_value();
  e.seed = seed.value_or(0);
  Notify(e, from);
  return "";
}

void Session::StartRun() {
  run_edits_.clear();
  changes_.clear();
  queued_.clear();
  queued_parse_.reset();
  moves_.clear();
  actions_.clear();
  ++run_id_;
}

std::string Session::Reload() {
  try {
    return Reloaded(ScenarioSource::FromFile(disk_file_));
  } catch (const std::exception& e) {
    return std::string("reload failed, the run goes on unchanged: ") + e.what();
  }
}

std::string Session::ReloadFrom(ScenarioSource source) {
  return Reloaded(std::move(source));
}

std::string Session::Reloaded(ScenarioSource source) {
  const long from = exp_->steps();
  try {
    ParsedScenario parsed = ParseScenario(source, cli_);
    std::unique_ptr<Experiment> exp = BuildExperiment(parsed);
    if (run_setup_) {
      exp_->mutable_recorder().AbandonStream();
      run_setup_(*exp);
    }
    source_ = std::move(source);
    disk_file_ = source_.file();
    applied_ = std::move(parsed);
    exp_ = std::move(exp);
  } catch (const std::exception& e) {
    return std::string("reload failed, the run goes on unchanged: ") + e.what();
  }
  loaded_ = applied_.params;
  base_ = cli_;
  reset_edits_.clear();
  StartRun();
  refusals_.clear();
  undo_.clear();
  redo_.clear();
  accepted_ = 0;
  SessionEvent e;
  e.kind = SessionEvent::Kind::kReload;
  e.source = std::make_shared<ScenarioSource>(source_);
  Notify(e, from);
  return "";
}

std::string Session::Branch(long step) {
  if (step < 0 || step > exp_->steps())
    return "branch: step " + std::to_string(step) + " is not in the run (0 ... " +
           std::to_string(exp_->steps()) + ")";
  const RunLog log = run_log().Before(step);
  // Edits asked for but not applied yet are asked for again on the branch.
  const std::vector<Override> asked = queued_;
  const long from = exp_->steps();
  try {
    // The new run streams its rows from step 0 to where the old one streamed them.
    if (run_setup_) exp_->mutable_recorder().AbandonStream();
    RunReplay replay(source_, log, run_setup_);
    replay.AdvanceTo(step, false);
    applied_ = replay.parsed();
    exp_ = replay.Release();
  } catch (const std::exception& e) {
    try {
      if (run_setup_) run_setup_(*exp_);
    } catch (const std::exception&) {
      // The old run's rows were thinned in memory: its file cannot be written again.
    }
    return std::string("branch failed, the run goes on unchanged: ") + e.what();
  }
  base_ = log.base;
  StartRun();
  changes_ = log.changes;
  run_edits_ = log.Edits();
  SessionEvent ev;
  ev.kind = SessionEvent::Kind::kBranch;
  ev.at = step;
  Notify(ev, from);
  // A replay of the record branches the same way, so these are not recorded again.
  auto observer = std::move(observer_);
  observer_ = nullptr;
  const std::vector<UndoStep> undo = undo_, redo = redo_;
  for (const Override& o : asked) Edit(o.key, o.value, o.origin);
  observer_ = std::move(observer);
  undo_ = undo;
  redo_ = redo;
  return "";
}

std::string Session::BakedText() const {
  return TunedScenarioText(source_, EffectiveOverrides(), disk_file_);
}

std::string Session::Restructure(const std::string& label, const StructureRewrite& rewrite,
                                 const std::string& origin) {
  std::string before, after;
  try {
    before = BakedText();
    after = rewrite(*exp_, before);
  } catch (const std::exception& e) {
    Reject("formation", e.what());
    return e.what();
  }
  if (std::string err = AdoptStructure(after, label, origin); !err.empty()) {
    Reject("formation", err);
    return err;
  }
  undo_.push_back({label, before, after, true});
  if (undo_.size() > 500) undo_.erase(undo_.begin());
  redo_.clear();
  return "";
}

std::string Session::RestructureFrom(ScenarioSource source, const std::string& command,
                                     const std::string& origin) {
  return AdoptStructure(source.text(), command, origin);
}

std::string Session::AdoptStructure(const std::string& text, const std::string& command,
                                    const std::string& origin) {
  const long from = exp_->steps();
  // Every edit is in the text: the new run starts from it alone (the seed included).
  // Messages about the new text name it after the file (its lines are the edited text's).
  const fs::path disk(disk_file_);
  const std::string name = (disk.parent_path() / (disk.stem().string() + ".edited.yaml")).string();
  ScenarioSource source = ScenarioSource::FromText(text, name, source_.dir());
  try {
    ParsedScenario parsed = ParseScenario(source, {});
    std::unique_ptr<Experiment> exp = BuildExperiment(parsed);
    exp->SetThreads(exp_->threads());
    if (run_setup_) {
      exp_->mutable_recorder().AbandonStream();
      run_setup_(*exp);
    }
    source_ = std::move(source);
    applied_ = std::move(parsed);
    exp_ = std::move(exp);
  } catch (const std::exception& e) {
    return std::string("not applied (the run goes on unchanged): the edited formation: ") + e.what();
  }
  base_.clear();
  reset_edits_.clear();
  StartRun();
  ++restructures_;
  SessionEvent e;
  e.kind = SessionEvent::Kind::kRestructure;
  e.key = command;
  e.origin = origin;
  e.source = std::make_shared<ScenarioSource>(source_);
  Notify(e, from);
  return "";
}

std::string Session::TunedYaml(const std::string& path, std::string* note) const {
  return TunedScenarioText(source_, EffectiveOverrides(), path, note);
}

bool Session::IsShipped(const std::string& path) {
  std::error_code ec;
  const fs::path dir = fs::weakly_canonical(ScenarioDir(), ec);
  const fs::path p = fs::weakly_canonical(path, ec);
  return fs::exists(p) && p.parent_path() == dir;
}

Session::SaveResult Session::Save(const std::string& path, bool overwrite, std::string* note) const {
  if (!overwrite && fs::exists(path)) return SaveResult::kNeedsConfirmation;
  const std::string text = TunedYaml(path, note);
  WriteFileAtomic(path, text);
  return SaveResult::kSaved;
}

}  // namespace formsim::sim
