#pragma once
/// \file An experiment: one scenario kind (formation, Mecanum AGV, inspection robot, velocity
/// control) built from a YAML file, stepped at a fixed rate, and described for drawing, plotting
/// and tuning without knowing anything about GL. Like Box2D's testbed samples, each kind
/// registers itself with FORMSIM_REGISTER_EXPERIMENT.

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "sim/core/draw.hpp"
#include "sim/core/json.hpp"
#include "sim/core/params.hpp"
#include "sim/core/recorder.hpp"
#include "sim/core/rng.hpp"
#include "sim/core/world.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

/// One line of a figure: a recorded column against time (or against `x_column`), or inline data.
struct SeriesSpec {
  std::string label;
  std::string column;    ///< recorder column for y; empty when x/y inline data are given
  std::string x_column;  ///< empty: time ("t")
  std::vector<double> x, y;  ///< inline data (e.g. a membership function)
  int color_index = -1;      ///< palette index; -1 = by series order
  bool dashed = false;
  bool markers_only = false;  ///< scatter (e.g. raw beacon fixes)
};

/// A figure, as exported by --plots and drawn live in the GUI.
struct FigureSpec {
  std::string id;     ///< file name stem: "phi_error" -> phi_error.png
  std::string title;  ///< e.g. "(b) Bearing error φ12"
  std::string x_label = "t [s]";
  std::string y_label;
  std::vector<SeriesSpec> series;
  std::vector<double> reference_lines;  ///< horizontal lines (targets, bounds)
  bool equal_aspect = false;            ///< trajectories: 1 m is 1 m on both axes
  double marker_x = std::numeric_limits<double>::quiet_NaN();  ///< a vertical marker (current input)
};

/// A table the GUI shows (e.g. fuzzy rules with their firing strengths).
struct TableSpec {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<double> row_strength;  ///< optional bar in [0, 1] per row
};

/// Something that happened: a collision, saturation, singular formation, filter fault.
struct Event {
  double time = 0.0;
  std::string kind;     ///< "collision", "saturation", "singular", "filter_fault", ...
  std::string robots;   ///< e.g. "R3" or "R1,R2"
  std::string message;
};

/// Values every experiment shares, read from the scenario's root by the loader.
struct ExperimentSetup {
  std::string file;         ///< scenario path (for messages)
  std::string name;         ///< scenario name
  std::string description;  ///< one line, for `formsim list`
  std::string type;         ///< experiment kind
  std::uint64_t seed = 1;
  double dt = 0.01;          ///< fixed world step, s
  double duration = 10.0;    ///< run length, s
  int record_every = 1;      ///< record one row every N steps
  YAML::Node scenario;       ///< the tree the experiment was built from (after --set), for saving
};

class Experiment {
 public:
  explicit Experiment(const ExperimentSetup& setup);
  virtual ~Experiment();

  /// One fixed step, always in this order: Control (controllers and estimators read the sensors
  /// and command the drives), world step (drives apply, Box2D integrates), Sense (sensors
  /// sample), then a recorded row every `record_every` steps.
  void Step();
  /// Applies UI edits and drags between steps. Reset requests are handled by the owner, which
  /// rebuilds the experiment from the (edited) scenario. Returns messages for rejected edits.
  std::vector<std::string> Apply(const PendingChanges& changes);

  double time() const { return time_; }
  double dt() const { return setup_.dt; }
  long steps() const { return steps_; }
  bool finished() const { return time_ >= setup_.duration - 0.5 * setup_.dt; }
  const ExperimentSetup& setup() const { return setup_; }

  World& world() { return world_; }
  const World& world() const { return world_; }
  ParamTable& params() { return params_; }
  const Recorder& recorder() const { return recorder_; }
  const std::vector<Event>& events() const { return events_; }

  /// Figures in the style of the paper (exported by --plots, drawn live in the GUI).
  virtual std::vector<FigureSpec> Figures() const = 0;
  /// Extra tables for the GUI (rules, per-link metrics...).
  virtual std::vector<TableSpec> Tables() const { return {}; }
  /// Draws the whole scene: world (patches, obstacles) then the experiment's own layers.
  void Draw(DrawSink& draw) const;
  /// Axis-aligned box that should be visible (for fit-all).
  virtual void Bounds(Vec2& lo, Vec2& hi) const;
  /// Metrics over the run so far (summary.json).
  virtual Json Summary() const = 0;
  /// A short human-readable table of the main metrics, printed by `formsim run`.
  virtual std::string SummaryTable() const = 0;

 protected:
  virtual void Control(double t) = 0;
  virtual void Sense(double t) = 0;
  virtual void Record(Recorder& rec) = 0;
  virtual void DrawScene(DrawSink& draw) const = 0;
  /// Called after Apply() changed parameters, so derived classes can refresh derived values.
  virtual void OnParamsChanged() {}
  /// Call at the end of the derived constructor: samples the sensors at t = 0 and records row 0.
  void Start();
  void AddEvent(const std::string& kind, const std::string& robots, const std::string& message);

  ExperimentSetup setup_;
  World world_;
  ParamTable params_;
  Recorder recorder_;
  Rng rng_;
  std::vector<Event> events_;

 private:
  void RecordRow();
  double time_ = 0.0;
  long steps_ = 0;
};

using ExperimentFactory =
    std::function<std::unique_ptr<Experiment>(const ExperimentSetup&, YamlReader& root)>;

/// Registry of experiment kinds (the `type:` of a scenario).
class ExperimentRegistry {
 public:
  static bool Register(const std::string& type, ExperimentFactory factory);
  static std::vector<std::string> Types();
  static const ExperimentFactory* Find(const std::string& type);
};

/// Loads a scenario file, applies `--set` assignments, reads the shared root keys (type, name,
/// description, seed, dt, duration, record_every), builds the experiment and checks that every
/// key was used. `seed_override` < 0 keeps the file's seed. Throws ScenarioError.
std::unique_ptr<Experiment> LoadExperiment(const std::string& file,
                                           const std::vector<std::string>& sets = {},
                                           long long seed_override = -1);
/// Same from an in-memory tree (the GUI's edited scenario); `file` is used in messages.
std::unique_ptr<Experiment> LoadExperimentFromNode(YAML::Node root, const std::string& file,
                                                   long long seed_override = -1);

/// Registers `Class` (constructible from (const ExperimentSetup&, YamlReader&)) as `type`.
#define FORMSIM_REGISTER_EXPERIMENT(type, Class)                                          \
  static const bool formsim_registered_##Class = ::formsim::sim::ExperimentRegistry::Register( \
      type, [](const ::formsim::sim::ExperimentSetup& s, ::formsim::sim::YamlReader& r) {  \
        return std::unique_ptr<::formsim::sim::Experiment>(new Class(s, r));              \
      })

}  // namespace formsim::sim
