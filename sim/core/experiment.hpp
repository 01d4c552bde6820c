#pragma once
/// \file An experiment: one scenario kind (formation, AGV, inspection robot, velocity control)
/// built from a checked configuration, stepped at a fixed rate, and described for drawing,
/// plotting and tuning without knowing anything about GL.
///
/// A kind is one self-contained, self-registering unit (like a Box2D testbed sample):
///
///   class FooExperiment : public ExperimentOf<FooConfig> {
///    public:
///     static FooConfig ReadConfig(YamlReader& root, const ExperimentSetup& setup);  // strict
///     FooExperiment(const ExperimentSetup& setup, const FooConfig& config);  // ends with Start()
///    protected:
///     void Control(double t) override;  void Sense(double t) override;
///     void ApplyTunables(const FooConfig& next) override;  // live edits
///     ...
///   };
///   FORMSIM_REGISTER_EXPERIMENT("foo", FooExperiment);

#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sim/core/draw.hpp"
#include "sim/core/event_log.hpp"
#include "sim/core/figure_spec.hpp"
#include "sim/core/json.hpp"
#include "sim/core/metrics.hpp"
#include "sim/core/provenance.hpp"
#include "sim/core/recorder.hpp"
#include "sim/core/rng.hpp"
#include "sim/core/thread_pool.hpp"
#include "sim/core/world.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

/// Values every experiment shares, read from the scenario's root by the loader.
struct ExperimentSetup {
  std::string file;         ///< scenario path (for messages)
  std::string dir;          ///< its folder (relative paths in the scenario resolve here)
  std::string name;         ///< scenario name
  std::string description;  ///< one line, for `formsim list`
  std::string type;         ///< experiment kind
  std::uint64_t seed = 1;
  double dt = 0.01;        ///< fixed world step, s
  double duration = 10.0;  ///< run length, s
  int record_every = 1;    ///< record one row every N steps
  Provenance provenance;   ///< what produced this run
};

/// A kind's parsed configuration, type-erased so the core can carry it.
struct ExperimentConfig {
  virtual ~ExperimentConfig() = default;
};
template <class C>
struct ConfigOf : ExperimentConfig {
  explicit ConfigOf(C v) : value(std::move(v)) {}
  C value;
};

/// A button an experiment offers beside its tunables (e.g. reload a fuzzy rule base from its
/// file), run between two steps like an edit.
struct ActionSpec {
  std::string id;     ///< also the script action argument, e.g. "reload_rules"
  std::string label;  ///< button text
  std::string group;  ///< GUI group, as Tune::Group
  std::string help;
};

class Experiment {
 public:
  explicit Experiment(const ExperimentSetup& setup);
  virtual ~Experiment();
  Experiment(const Experiment&) = delete;
  Experiment& operator=(const Experiment&) = delete;

  /// One fixed step, always in this order: Control (controllers and estimators read the sensors
  /// and command the drives), world step (drives apply, Box2D integrates) with the kind's
  /// Predict items beside it, Sense (sensors sample), then a recorded row every `record_every`
  /// steps.
  void Step();
  /// Takes the live tunables of `config`, a configuration of this kind read from the scenario
  /// with the user's edits (the session has checked it). Call between two steps.
  void Retune(const ExperimentConfig& config) { OnRetune(config); }
  /// A drag while paused: moves robot or obstacle `name` to p. Returns "" or why not.
  std::string Move(const std::string& name, Vec2 p);
  /// Adds a mid-run change to the run's provenance.
  void NoteOverride(const Override& o) { setup_.provenance.overrides.push_back(o); }

  double time() const { return time_; }
  double dt() const { return setup_.dt; }
  long steps() const { return steps_; }
  /// The run has ended: it reached its duration, or stopped early (numerical fault, interrupt).
  bool finished() const {
    return !stop_reason_.empty() || time_ >= setup_.duration - 0.5 * setup_.dt;
  }
  /// How the run ended so far: "running", "completed", "numerical_fault" or "interrupted".
  std::string status() const;
  /// Why the run stopped early ("" when it did not).
  const std::string& stop_reason() const { return stop_reason_; }
  /// Stops the run now (Ctrl-C, SIGTERM): the results so far stay valid and are marked so.
  void Interrupt(const std::string& why);
  const ExperimentSetup& setup() const { return setup_; }
  /// Threads for the independent work inside a step (default ThreadPool::DefaultThreads(), the
  /// CLI's --threads). The results are the same bytes for any number; call between two steps.
  void SetThreads(int threads);
  int threads() const { return pool_->threads(); }

  World& world() { return world_; }
  const World& world() const { return world_; }
  const Recorder& recorder() const { return recorder_; }
  /// For the owner of the run (streaming the rows to disk, limiting the history kept).
  Recorder& mutable_recorder() { return recorder_; }
  const EventLog& events() const { return events_; }

  /// Figures in the style of the paper (exported by --plots, drawn live in the GUI).
  virtual std::vector<FigureSpec> Figures() const = 0;
  /// Buttons this experiment offers (none by default).
  virtual std::vector<ActionSpec> Actions() const { return {}; }
  /// Runs action `id` between two steps. Returns "" or why it failed (then nothing changed).
  virtual std::string RunAction(const std::string& id) { return "no action '" + id + "'"; }
  /// An optional capability of this kind (sim::StructureEditing, formation::FormationEditing,
  /// ...): this experiment seen as `Capability` when its kind offers it, else null. The base
  /// keeps only what every kind has; what some kinds can do is a capability they derive from.
  template <class Capability>
  const Capability* As() const {
    return dynamic_cast<const Capability*>(this);
  }
  /// Extra tables for the GUI beyond the results (rules with firing strengths...).
  virtual std::vector<TableSpec> Tables() const { return {}; }
  /// Draws the whole scene: world (patches, obstacles) then the experiment's own layers.
  void Draw(DrawSink& draw) const;
  /// Draws the experiment's own layers only (robots, trails, estimates), without the world's
  /// patches and obstacles: another run drawn over this one (a pinned run in the GUI).
  void DrawOverlay(DrawSink& draw) const { DrawScene(draw); }
  /// Axis-aligned box that should be visible (for fit-all).
  virtual void Bounds(Vec2& lo, Vec2& hi) const;
  /// What a presentation camera keeps in view: each robot's position and size (`bodies`: x, y
  /// and the radius of its circumscribed circle, m) and the points of their trails drawn in the
  /// last `seconds` (`trails`). Appends to both. Default: the robots, no trails.
  virtual void FocusPoints(std::vector<Vec2>& bodies, std::vector<double>& radii,
                           std::vector<Vec2>& trails, double seconds) const;
  /// The bounding box of the finite trail points FocusPoints would give for `seconds`, without
  /// collecting them (a camera that frames them each frame); false when there are none.
  virtual bool TrailBox(double /*seconds*/, Vec2& /*lo*/, Vec2& /*hi*/) const { return false; }
  /// Metrics over the run so far: summary.json's `results`, the printed and GUI tables.
  virtual Metrics Results() const = 0;
  /// summary.json: scenario, provenance, steps, results, event counts and the first events.
  Json Summary() const;
  /// What `formsim run` prints: the results' tables and the event counts.
  std::string SummaryText() const;

 protected:
  virtual void Control(double t) = 0;
  virtual void Sense(double t) = 0;
  /// Work of the coming Sense that needs only the state before the world step (the estimators'
  /// time updates from this step's commands): PredictItems() independent items, taken by the
  /// pool's other threads while this one steps Box2D (then it helps), so that Box2D, which only
  /// one thread can run, is not alone on the machine. Called after Control; each item writes
  /// only its own data (a run that stops at the world step's state check keeps the predicted
  /// estimates). Default: none.
  virtual std::size_t PredictItems() const { return 0; }
  virtual void Predict(std::size_t /*begin*/, std::size_t /*end*/) {}
  virtual void DrawScene(DrawSink& draw) const = 0;
  virtual void OnRetune(const ExperimentConfig& config) = 0;
  /// Call at the end of the derived constructor, after declaring the recorder's channels:
  /// samples the sensors at t = 0 and records row 0.
  void Start();
  /// A non-finite or diverged value that the experiment found itself (an estimate, a command):
  /// raises a numerical_fault event for `robots` and stops the run after this step.
  void NumericalFault(const std::string& robots, const std::string& message);
  /// The pool for a step's independent work (see thread_pool.hpp for the contract).
  ThreadPool& pool() const { return *pool_; }
  /// Records an event now.
  void AddEvent(const std::string& kind, const std::string& robots, const std::string& message,
                const std::string& subject = "") {
    events_.Add(time_, kind, robots, message, subject);
  }

  ExperimentSetup setup_;
  std::unique_ptr<ThreadPool> pool_;  ///< before everything its tasks touch
  World world_;
  Recorder recorder_;  ///< "t" is declared first by the base
  Rng rng_;
  EventLog events_;

 private:
  /// After the world step: every robot's pose and velocity must be finite.
  bool CheckRobots();
  /// After a recorded row: every sampled value must be finite.
  void CheckRow();
  double time_ = 0.0;
  long steps_ = 0;
  std::string event_robots_, event_message_;  ///< text of the events raised by Step
  std::string stop_status_;                   ///< "numerical_fault" or "interrupted" once stopped
  std::string stop_reason_;
};

/// Base of a kind with configuration type C: keeps the configuration and routes Retune to
/// ApplyTunables with the right type.
template <class C>
class ExperimentOf : public Experiment {
 public:
  using Config = C;
  ExperimentOf(const ExperimentSetup& setup, const C& config) : Experiment(setup), cfg_(config) {}
  const C& config() const { return cfg_; }

 protected:
  /// Takes the live tunables of `next` (read from the edited scenario; everything that applies
  /// only on reset is unchanged).
  virtual void ApplyTunables(const C& next) = 0;
  C cfg_;

 private:
  void OnRetune(const ExperimentConfig& config) final {
    const auto* c = dynamic_cast<const ConfigOf<C>*>(&config);
    if (c == nullptr) throw std::logic_error("Retune with a configuration of another kind");
    ApplyTunables(c->value);
  }
};

/// One kind of experiment: how to read its configuration and how to build it.
struct ExperimentKind {
  std::string type;
  std::shared_ptr<const ExperimentConfig> (*read)(YamlReader& root,
                                                  const ExperimentSetup& setup) = nullptr;
  std::unique_ptr<Experiment> (*build)(const ExperimentSetup& setup,
                                       const ExperimentConfig& config) = nullptr;
};

/// Registry of experiment kinds (the `type:` of a scenario).
class ExperimentRegistry {
 public:
  static bool Register(const ExperimentKind& kind);
  static std::vector<std::string> Types();
  static const ExperimentKind* Find(const std::string& type);
};

template <class E>
bool RegisterExperimentKind(const char* type) {
  using C = typename E::Config;
  ExperimentKind k;
  k.type = type;
  k.read = [](YamlReader& root,
              const ExperimentSetup& setup) -> std::shared_ptr<const ExperimentConfig> {
    return std::make_shared<ConfigOf<C>>(E::ReadConfig(root, setup));
  };
  k.build = [](const ExperimentSetup& setup,
               const ExperimentConfig& config) -> std::unique_ptr<Experiment> {
    const auto* c = dynamic_cast<const ConfigOf<C>*>(&config);
    if (c == nullptr) throw std::logic_error("build with a configuration of another kind");
    return std::make_unique<E>(setup, c->value);
  };
  return ExperimentRegistry::Register(k);
}

/// Registers `Class` (an ExperimentOf<Config> with a static ReadConfig) as `type`.
#define FORMSIM_REGISTER_EXPERIMENT(type, Class) \
  static const bool formsim_registered_##Class = ::formsim::sim::RegisterExperimentKind<Class>(type)

}  // namespace formsim::sim
