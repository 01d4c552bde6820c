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

#include "sim/session/run_log.hpp"
#include "sim/scenario/scenario.hpp"

namespace formsim::sim {

/// Something done to a session, with the step of the run it happened at: what a session record
/// (`formsim gui --session FILE`) keeps so that `formsim replay` can do it again.
struct SessionEvent {
  enum class Kind {
    kLoad,    ///< a scenario loaded: `source`, command-line `overrides`
    kEdit,    ///< an accepted edit: key, value, origin
    kApply,   ///< queued edits, drags and actions applied (one Retune)
    kAction,  ///< an accepted action request: key = id, origin
    kMove,    ///< a drag request: key = name, x, y
    kReset,   ///< a reset, with `seed` when one was given
    kReload,  ///< the file re-read: `source` = its text then
    kBranch,  ///< the run restarted from its own step `at`
    kRestructure,  ///< the scenario's structure changed: `source` = the new text, key = the
                   ///< command ("" for undo / redo), origin
    kNote,    ///< for the record only (pin, unpin, seeds, restore): key = what, value = detail
    kEnd,     ///< the last step of the record
  };
  Kind kind = Kind::kNote;
  long step = 0;  ///< steps of the current run when it happened
  std::string key, value, origin;
  double x = 0, y = 0;
  bool has_seed = false;
  std::uint64_t seed = 0;
  long at = 0;
  std::shared_ptr<const ScenarioSource> source;
  std::vector<Override> overrides;
};

class Session {
 public:
  /// Loads `file` with command-line overrides (--set, --seed). Throws ScenarioError.
  Session(const std::string& file, std::vector<Override> cli_overrides);
  /// Same with `--set` strings and a seed (< 0: the scenario's).
  Session(const std::string& file, const std::vector<std::string>& sets, long long seed);
  /// A scenario held in memory (a replayed session record). Throws ScenarioError.
  Session(ScenarioSource source, std::vector<Override> cli_overrides);

  /// Called with everything done to the session (accepted edits, applies, drags, actions,
  /// resets, reloads, branches), each with its step: the session record of the GUI.
  void SetObserver(std::function<void(const SessionEvent&)> observer) {
    observer_ = std::move(observer);
  }

  /// Called with every experiment the session builds (now, and after each reset or reload),
  /// e.g. to stream its rows to disk and bound the history kept in memory.
  void SetRunSetup(std::function<void(Experiment&)> setup);

  Experiment& exp() { return *exp_; }
  const Experiment& exp() const { return *exp_; }
  /// The scenario file on disk (also after structural changes, whose text is named
  /// `<stem>.edited.yaml` in messages).
  const std::string& file() const { return disk_file_; }
  const ScenarioSource& source() const { return source_; }
  /// Every tunable with the value the running experiment uses.
  const ParamTable& params() const { return applied_.params; }
  /// The `lesson:` block of the scenario (present = false for a plain scenario).
  const LessonDef& lesson() const { return applied_.lesson; }
  std::uint64_t seed() const { return exp_->setup().seed; }
  /// The command-line overrides the scenario was loaded with.
  const std::vector<Override>& cli_overrides() const { return cli_; }
  /// Every tunable as loaded (the file with the command-line overrides): what "revert" goes
  /// back to and what "edited" is measured against.
  const ParamTable& loaded_params() const { return loaded_; }
  /// The value (YAML text) the next reset would run `key` with: a waiting or queued edit, else
  /// the value in use. "" for an unknown key.
  std::string EffectiveValue(const std::string& key) const;
  /// The loaded value of `key` as text ("" for an unknown key).
  std::string LoadedValue(const std::string& key) const;
  /// True when the effective value of `key` differs from the loaded one.
  bool IsEdited(const std::string& key) const;

  /// Asks for an edit of tunable `key` (value as YAML text). Returns "" when accepted, else the
  /// reason (also kept in rejected() and refusal()). Live tunables apply before the next step;
  /// OnReset ones wait for Reset(). `origin` names the edit in messages and provenance.
  /// Every accepted edit can be undone: `continues_gesture` merges it with the previous edit of
  /// the same key into one undo step (a slider dragged over many frames).
  std::string Edit(const std::string& key, const std::string& value,
                   const std::string& origin = "GUI edit", bool continues_gesture = false);
  /// Edits the last edited tunable back to its value before that edit (through Edit, origin
  /// "undo"). Returns "" or why not (nothing to undo, or the edit is refused now).
  std::string Undo();
  /// Does again the edit the last Undo took back (origin "redo").
  std::string Redo();
  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  /// "k_l 0.15 -> 0.4": what Undo (Redo) would take back (do again); "" when nothing.
  std::string UndoText() const;
  std::string RedoText() const;
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
  /// Rewrites the scenario text for a structural change (`now`: the running experiment).
  using StructureRewrite =
      std::function<std::string(const Experiment& now, const std::string& text)>;
  /// Changes the scenario's structure (a formation's robots, leaders, laws, shape) through the
  /// kind's capability (e.g. formation::Restructure, which calls this): the scenario with every
  /// edit so far written into its text is rewritten by `rewrite` (which throws
  /// std::runtime_error with the reason when the change cannot apply), then read by the one
  /// loader (every check of a load applies: a refused change leaves everything as it was) and a
  /// new run starts from it, the robots where they are now. `label` is the change's text form
  /// ("add l_phi R1 0.5 -0.3"): the record's `restructure` key and the undo text. The new text
  /// is the session's scenario from then on: resets, branches, Save and the session record use
  /// it, and Undo / Redo take structural changes back like edits. Returns "" or why it was
  /// refused.
  std::string Restructure(const std::string& label, const StructureRewrite& rewrite,
                          const std::string& origin = "GUI edit");
  /// Adopts `source` as the restructured scenario (a replayed session record).
  std::string RestructureFrom(ScenarioSource source, const std::string& command,
                              const std::string& origin);
  /// Number of structural changes applied since the file was loaded (undo included).
  int restructures() const { return restructures_; }
  /// Re-reads the file from disk with the command-line overrides only (GUI edits are dropped).
  /// Returns "" or the reason; on failure everything stays as it was.
  std::string Reload();
  /// Reload with `source` as the file's text (a replayed session record).
  std::string ReloadFrom(ScenarioSource source);
  /// Restarts the current run from its own step `step` (0 ... steps()): the run is replayed
  /// from step 0 with the same start and the same changes at the same steps up to `step`
  /// (changes of `step` itself are not applied), so the branch starts from the exact state of
  /// the whole world at that step. Later changes are dropped; edits waiting for a reset stay.
  /// Costs `step` steps. Returns "" or why not (the run then goes on unchanged).
  std::string Branch(long step);
  /// How the current run came about (start and changes with their steps): replaying it gives
  /// the run again exactly.
  RunLog run_log() const { return {base_, changes_}; }
  /// Counts the runs of this session: changes with every reset, reload and branch.
  long run_id() const { return run_id_; }
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
  void Notify(SessionEvent e, long step = -1) const;  ///< step -1: the current one
  /// Adopts a new run (reset, reload, branch): clears what belonged to the old one.
  void StartRun();
  std::string Reloaded(ScenarioSource source);

  /// Reads `text` as the new scenario and starts a run from it. Returns "" or why not.
  std::string AdoptStructure(const std::string& text, const std::string& command,
                             const std::string& origin);
  /// Undo / redo of a structural change: the scenario `text` with the robots where they are.
  std::string RestructureTo(const std::string& text, const std::string& origin);
  /// The scenario's text with every effective edit written into it.
  std::string BakedText() const;

  /// An edit (key, values) or a structural change (`structure`: before / after are the
  /// scenario texts, key the command).
  struct UndoStep {
    std::string key, before, after;
    bool structure = false;
  };

  ScenarioSource source_;
  std::string disk_file_;             ///< what Reload reads
  std::vector<Override> cli_;         ///< --set / --seed as given
  std::vector<Override> base_;        ///< in force from the start of the current run
  std::vector<Override> run_edits_;   ///< applied during the current run (with their step)
  std::vector<RunChange> changes_;    ///< everything applied during the current run
  std::vector<Override> queued_;      ///< accepted live edits, applied at the next ApplyPending
  std::vector<Override> reset_edits_; ///< accepted OnReset edits, waiting for a reset
  std::optional<ParsedScenario> queued_parse_;  ///< the scenario with queued_ applied
  ParsedScenario applied_;
  ParamTable loaded_;
  std::unique_ptr<Experiment> exp_;
  std::function<void(Experiment&)> run_setup_;
  std::function<void(const SessionEvent&)> observer_;
  std::vector<UndoStep> undo_, redo_;
  long run_id_ = 0;
  struct MoveRequest {
    std::string name;
    double x = 0, y = 0;
  };
  std::vector<MoveRequest> moves_;
  std::vector<Override> actions_;  ///< queued actions (key "action", value the id)
  std::vector<std::string> rejected_;
  std::map<std::string, std::string> refusals_;
  int accepted_ = 0;
  int restructures_ = 0;
};

}  // namespace formsim::sim
