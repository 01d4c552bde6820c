#pragma once
/// \file The tuning session behind the GUI, free of any GL: the loaded scenario tree, the running
/// experiment, edits queued as sim::PendingChanges and applied between steps, reset from the
/// edited tree, and saving the tuned scenario. Tests drive it directly.

#include <yaml-cpp/yaml.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "sim/core/experiment.hpp"

namespace formsim::app {

class Session {
 public:
  /// Loads `file` with `--set` assignments; `seed` < 0 keeps the scenario's. Throws on errors.
  Session(const std::string& file, const std::vector<std::string>& sets, long long seed);

  sim::Experiment& exp() { return *exp_; }
  const sim::Experiment& exp() const { return *exp_; }
  const std::string& file() const { return file_; }
  /// The scenario as edited so far (what a reset rebuilds and Save writes).
  const YAML::Node& tree() const { return tree_; }
  std::uint64_t seed() const { return exp_->setup().seed; }

  /// Queues a parameter edit (value as YAML text). Live parameters apply before the next step;
  /// `requires_reset` ones are stored in the tree and apply on reset. Malformed values are
  /// rejected at once (see rejected()).
  void Edit(const std::string& key, const std::string& value);
  /// Queues a drag of a robot or obstacle to (x, y).
  void Move(const std::string& name, double x, double y);
  /// Applies the queued changes now (between steps; also called while paused).
  void ApplyPending();
  /// Applies pending changes, then one fixed step.
  void Step();
  /// Rebuilds the experiment from the edited tree; `seed` < 0 keeps the current seed.
  void Reset(long long seed = -1);
  bool has_pending() const { return !pending_.empty(); }

  /// Edits that were refused, newest last, each "t=1.23 s key: reason".
  const std::vector<std::string>& rejected() const { return rejected_; }
  /// Edits of requires_reset parameters waiting for a reset: key -> value.
  const std::map<std::string, std::string>& waiting_for_reset() const { return waiting_; }
  /// Number of edits accepted since the last load (shown as "tuned" in the GUI).
  int accepted_edits() const { return accepted_; }

  enum class SaveResult { kSaved, kNeedsConfirmation };
  /// Writes the tuned scenario to `path` (temp file + rename). Refuses to overwrite an existing
  /// file, and above all a shipped scenario, unless `overwrite` is set. Throws on I/O errors.
  SaveResult Save(const std::string& path, bool overwrite = false) const;
  /// The text Save would write.
  std::string TunedYaml() const;
  /// True when `path` is one of the scenarios shipped in assets/scenarios.
  static bool IsShipped(const std::string& path);

 private:
  void Reject(const std::string& key, const std::string& why);
  std::string file_;
  YAML::Node tree_;
  std::unique_ptr<sim::Experiment> exp_;
  sim::PendingChanges pending_;
  std::vector<std::string> rejected_;
  std::map<std::string, std::string> waiting_;
  int accepted_ = 0;
};

/// Formats a double so that parsing it back gives the same bits.
std::string ExactDouble(double v);

}  // namespace formsim::app
