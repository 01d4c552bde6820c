#pragma once
/// \file A tuning session, free of any GUI: the scenario's text, the running experiment and
/// the user's edits (MuJoCo-simulate style: the UI asks, the session applies between steps).
/// Every edit is checked at once by reading the whole scenario with it, through the same
/// reader as the loader, so an edit the loader would refuse never reaches the simulation or a
/// later reset. Resets and reloads that fail leave the running experiment as it was.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/core/scenario.hpp"

namespace formsim::sim {

class Session {
 public:
  /// Loads `file` with command-line overrides (--set, --seed). Throws ScenarioError.
  Session(const std::string& file, std::vector<Override> cli_overrides);
  /// Same with `--set` strings and a seed (< 0: the scenario's).
  Session(const std::string& file, const std::vector<std::string>& sets, long long seed);

  /// Called with every experiment the session builds (now, and after each reset or reload),
  /// e.g. to stream its rows to disk and bound the history kept in memory.
  void SetRunSetup(std::function<void(Experiment&)> setup);

  Experiment& exp() { return *exp_; }
  const Experiment& exp() const { return *exp_; }
  const std::string& file() const { return source_.file(); }
  const ScenarioSource& source() const { return source_; }
  /// Every tunable with the value the running experiment uses.
  const ParamTable& params() const { return applied_.params; }
  std::uint64_t seed() const { return exp_->setup().seed; }

  /// Asks for an edit of tunable `key` (value as YAML text). Returns "" when accepted, else the
  /// reason (also kept in rejected() and refusal()). Live tunables apply before the next step;
  /// OnReset ones wait for Reset(). `origin` names the edit in messages and provenance.
  std::string Edit(const std::string& key, const std::string& value,
                   const std::string& origin = "GUI edit");
  /// Queues one of the experiment's actions (Experiment::Actions), run between two steps.
  /// Returns "" or why it is refused (unknown action).
  std::string Action(const std::string& id, const std::string& origin = "GUI action");
  /// Queues a drag of a robot or obstacle to (x, y).
  void Move(const std::string& name, double x, double y);
  /// Applies queued edits and drags now (between steps; also while paused).
  void ApplyPending();
  /// Applies pending changes, then one fixed step.
  void Step();
  /// Rebuilds from the file and every accepted edit (with `seed` when given). Returns "" or
  /// the reason it failed, in which case the running experiment stays.
  std::string Reset(std::optional<std::uint64_t> seed = std::nullopt);
  /// Re-reads the file from disk with the command-line overrides only (GUI edits are dropped).
  /// Returns "" or the reason; on failure everything stays as it was.
  std::string Reload();
  bool has_pending() const { return !queued_.empty() || !moves_.empty() || !actions_.empty(); }

  /// Edits that were refused, newest last, each "t=1.23 s key: reason".
  const std::vector<std::string>& rejected() const { return rejected_; }
  /// Why the last edit of `key` was refused; "" when it was accepted or never refused.
  std::string refusal(const std::string& key) const;
  /// Edits of OnReset tunables waiting for a reset: key -> value.
  std::map<std::string, std::string> waiting_for_reset() const;
  /// Number of edits accepted since the file was loaded.
  int accepted_edits() const { return accepted_; }
  /// Every change on top of the file that a reset would run with, last value per key.
  std::vector<Override> EffectiveOverrides() const;

  enum class SaveResult { kSaved, kNeedsConfirmation };
  /// Writes the tuned scenario to `path` (temp file + rename): the file's own text with only
  /// the changed values rewritten and relative file paths adjusted to the new folder. Refuses
  /// to overwrite an existing file unless `overwrite`. `note` receives a remark (e.g. comments
  /// could not be kept). Throws on I/O errors or if the result would not load.
  SaveResult Save(const std::string& path, bool overwrite = false, std::string* note = nullptr) const;
  /// The text Save would write into `path`.
  std::string TunedYaml(const std::string& path, std::string* note = nullptr) const;
  /// True when `path` is one of the scenarios shipped in assets/scenarios.
  static bool IsShipped(const std::string& path);

 private:
  void Reject(const std::string& key, const std::string& why);
  std::vector<Override> All(bool with_reset_edits) const;

  ScenarioSource source_;
  std::vector<Override> cli_;         ///< --set / --seed as given
  std::vector<Override> base_;        ///< in force from the start of the current run
  std::vector<Override> run_edits_;   ///< applied during the current run (with their step)
  std::vector<Override> queued_;      ///< accepted live edits, applied at the next ApplyPending
  std::vector<Override> reset_edits_; ///< accepted OnReset edits, waiting for a reset
  std::optional<ParsedScenario> queued_parse_;  ///< the scenario with queued_ applied
  ParsedScenario applied_;
  std::unique_ptr<Experiment> exp_;
  std::function<void(Experiment&)> run_setup_;
  struct MoveRequest {
    std::string name;
    double x = 0, y = 0;
  };
  std::vector<MoveRequest> moves_;
  std::vector<Override> actions_;  ///< queued actions (key "action", value the id)
  std::vector<std::string> rejected_;
  std::map<std::string, std::string> refusals_;
  int accepted_ = 0;
};

}  // namespace formsim::sim
