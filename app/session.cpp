#include "app/session.hpp"

#include <cstdio>
#include <filesystem>

#include "app/scenario_files.hpp"
#include "sim/core/run_output.hpp"

namespace fs = std::filesystem;

namespace formsim::app {

std::string ExactDouble(double v) {
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

Session::Session(const std::string& file, const std::vector<std::string>& sets, long long seed)
    : file_(file) {
  tree_ = sim::LoadYamlFile(file);
  for (const auto& a : sets) {
    const std::string err = sim::ApplySet(tree_, a);
    if (!err.empty()) throw sim::ScenarioError(file, 0, 0, "", err);
  }
  if (seed >= 0) tree_["seed"] = seed;
  // Build from a copy: the loader may mark or touch nodes, our tree stays the user's text.
  exp_ = sim::LoadExperimentFromNode(YAML::Clone(tree_), file_);
}

void Session::Reject(const std::string& key, const std::string& why) {
  char t[32];
  std::snprintf(t, sizeof(t), "t=%.2f s ", exp_->time());
  rejected_.push_back(t + key + ": " + why);
  if (rejected_.size() > 50) rejected_.erase(rejected_.begin());
}

void Session::Edit(const std::string& key, const std::string& value) {
  sim::Param* p = exp_->params().Find(key);
  if (p == nullptr) return Reject(key, "unknown parameter");
  // Validate on a scratch copy of the parameter, so nothing of the experiment changes here.
  sim::Param scratch = *p;
  double d = 0;
  int i = 0;
  bool b = false;
  scratch.d = p->d ? &d : nullptr;
  scratch.i = p->i ? &i : nullptr;
  scratch.b = p->b ? &b : nullptr;
  const std::string err = sim::ParamTable::SetFromString(scratch, value);
  if (!err.empty()) return Reject(key, err);
  if (p->requires_reset) {
    YAML::Node v = YAML::Load(sim::ParamTable::ToString(scratch));
    const std::string e2 = sim::SetAtPath(tree_, key, v);
    if (!e2.empty()) return Reject(key, e2);
    waiting_[key] = sim::ParamTable::ToString(scratch);
    ++accepted_;
    return;
  }
  pending_.edits.push_back({key, value});
}

void Session::Move(const std::string& name, double x, double y) {
  pending_.moves.push_back({name, x, y});
}

void Session::ApplyPending() {
  if (pending_.empty()) return;
  sim::PendingChanges changes;
  std::swap(changes, pending_);
  // Apply edit by edit, so a refused one is reported with its key and the others still apply.
  for (const auto& e : changes.edits) {
    sim::PendingChanges one;
    one.edits.push_back(e);
    const auto errors = exp_->Apply(one);
    if (!errors.empty()) {
      Reject(e.key, errors.front());
      continue;
    }
    // Keep the tree in step so a reset or a save keeps the tuned value.
    const sim::Param* p = exp_->params().Find(e.key);
    const std::string err = sim::SetAtPath(tree_, e.key, YAML::Load(sim::ParamTable::ToString(*p)));
    if (!err.empty()) Reject(e.key, err);
    ++accepted_;
  }
  if (!changes.moves.empty()) {
    sim::PendingChanges moves;
    moves.moves = changes.moves;
    for (const auto& err : exp_->Apply(moves)) Reject("move", err);
  }
}

void Session::Step() {
  ApplyPending();
  exp_->Step();
}

void Session::Reset(long long seed) {
  pending_ = {};
  if (seed >= 0)
    tree_["seed"] = seed;
  else
    tree_["seed"] = static_cast<long long>(exp_->setup().seed);
  exp_ = sim::LoadExperimentFromNode(YAML::Clone(tree_), file_);
  waiting_.clear();
}

std::string Session::TunedYaml() const {
  YAML::Emitter out;
  out.SetIndent(2);
  out.SetDoublePrecision(17);
  out << tree_;
  return "# Tuned with formsim gui from " + fs::path(file_).filename().string() + "\n" +
         out.c_str() + "\n";
}

bool Session::IsShipped(const std::string& path) {
  std::error_code ec;
  const fs::path dir = fs::weakly_canonical(ScenarioDir(), ec);
  const fs::path p = fs::weakly_canonical(path, ec);
  return fs::exists(p) && p.parent_path() == dir;
}

Session::SaveResult Session::Save(const std::string& path, bool overwrite) const {
  if (!overwrite && fs::exists(path)) return SaveResult::kNeedsConfirmation;
  sim::WriteFileAtomic(path, TunedYaml());
  return SaveResult::kSaved;
}

}  // namespace formsim::app
