#include "sim/core/session.hpp"

#include <cstdio>
#include <filesystem>

#include "sim/core/run_output.hpp"
#include "sim/core/scenario_files.hpp"
#include "sim/core/scenario_save.hpp"

namespace fs = std::filesystem;

namespace formsim::sim {

Session::Session(const std::string& file, std::vector<Override> cli_overrides)
    : source_(ScenarioSource::FromFile(file)), cli_(std::move(cli_overrides)), base_(cli_) {
  applied_ = ParseScenario(source_, base_);
  exp_ = BuildExperiment(applied_);
}

Session::Session(const std::string& file, const std::vector<std::string>& sets, long long seed)
    : Session(file, CliOverrides(sets, seed)) {}

void Session::SetRunSetup(std::function<void(Experiment&)> setup) {
  run_setup_ = std::move(setup);
  if (run_setup_) run_setup_(*exp_);
}

void Session::Reject(const std::string& key, const std::string& why) {
  char t[32];
  std::snprintf(t, sizeof(t), "t=%.2f s ", exp_->time());
  rejected_.push_back(t + key + ": " + why);
  if (rejected_.size() > 50) rejected_.erase(rejected_.begin());
  refusals_[key] = why;
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

std::map<std::string, std::string> Session::waiting_for_reset() const {
  std::map<std::string, std::string> out;
  for (const Override& o : reset_edits_) out[o.key] = o.value;
  return out;
}

std::string Session::Edit(const std::string& key, const std::string& value,
                          const std::string& origin) {
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
  return "";
}

void Session::Move(const std::string& name, double x, double y) { moves_.push_back({name, x, y}); }

std::string Session::Action(const std::string& id, const std::string& origin) {
  for (const ActionSpec& a : exp_->Actions())
    if (a.id == id) {
      actions_.push_back({"action", id, origin, -1});
      return "";
    }
  const std::string why = "no action '" + id + "' in this scenario";
  Reject("action", why);
  return why;
}

void Session::ApplyPending() {
  if (!queued_.empty() && queued_parse_) {
    try {
      exp_->Retune(*queued_parse_->config);
      applied_ = std::move(*queued_parse_);
      for (Override o : queued_) {
        o.step = exp_->steps();
        run_edits_.push_back(o);
        exp_->NoteOverride(o);
      }
    } catch (const std::exception& e) {
      for (const Override& o : queued_) Reject(o.key, std::string("could not apply: ") + e.what());
    }
  }
  queued_.clear();
  queued_parse_.reset();
  for (const MoveRequest& m : moves_) {
    const std::string err = exp_->Move(m.name, {m.x, m.y});
    if (!err.empty()) Reject("move", err);
  }
  moves_.clear();
  for (Override a : actions_) {
    const std::string err = exp_->RunAction(a.value);
    if (!err.empty()) {
      Reject("action " + a.value, err);
      continue;
    }
    a.step = exp_->steps();
    exp_->NoteOverride(a);
  }
  actions_.clear();
}

void Session::Step() {
  ApplyPending();
  exp_->Step();
}

std::string Session::Reset(std::optional<std::uint64_t> seed) {
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
  run_edits_.clear();
  queued_.clear();
  queued_parse_.reset();
  reset_edits_.clear();
  moves_.clear();
  actions_.clear();
  return "";
}

std::string Session::Reload() {
  try {
    ScenarioSource source = ScenarioSource::FromFile(source_.file());
    ParsedScenario parsed = ParseScenario(source, cli_);
    std::unique_ptr<Experiment> exp = BuildExperiment(parsed);
    if (run_setup_) {
      exp_->mutable_recorder().AbandonStream();
      run_setup_(*exp);
    }
    source_ = std::move(source);
    applied_ = std::move(parsed);
    exp_ = std::move(exp);
  } catch (const std::exception& e) {
    return std::string("reload failed, the run goes on unchanged: ") + e.what();
  }
  base_ = cli_;
  run_edits_.clear();
  queued_.clear();
  queued_parse_.reset();
  reset_edits_.clear();
  moves_.clear();
  actions_.clear();
  refusals_.clear();
  accepted_ = 0;
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
