#pragma once
/// \file The parameter table: every tunable value of an experiment, once. The GUI renders it
/// with one generic panel, `--set key=value` and the saved scenario use the same keys, which
/// are the YAML paths of the values (`robots.R2.controller.k_l`; list items by `name` or index).

#include <functional>
#include <string>
#include <vector>

namespace formsim::sim {

/// One tunable value. Exactly one of the pointers is set, matching `kind`.
struct Param {
  enum class Kind { kDouble, kInt, kBool, kChoice };
  std::string key;    ///< YAML path, also the --set key
  std::string group;  ///< GUI grouping, e.g. "Gains/R2" or "Noise/beacon"
  std::string label;  ///< short label shown next to the widget
  std::string unit;   ///< e.g. "m", "rad", "1/s"; empty when dimensionless
  Kind kind = Kind::kDouble;
  double* d = nullptr;
  int* i = nullptr;
  bool* b = nullptr;
  std::vector<std::string> choices;  ///< for kChoice: the YAML strings, `i` is the index
  double min = 0.0, max = 1.0;       ///< slider range (values outside are allowed from YAML)
  bool log_scale = false;            ///< slider in log scale (noise variances, gains)
  bool requires_reset = false;       ///< true: takes effect on the next reset, not live
};

/// A list of parameters owned by an experiment (the pointers point into the experiment).
class ParamTable {
 public:
  Param& AddDouble(const std::string& key, const std::string& group, const std::string& label,
                   double* value, double min, double max, const std::string& unit = "",
                   bool log_scale = false);
  Param& AddInt(const std::string& key, const std::string& group, const std::string& label,
                int* value, int min, int max);
  Param& AddBool(const std::string& key, const std::string& group, const std::string& label,
                 bool* value);
  Param& AddChoice(const std::string& key, const std::string& group, const std::string& label,
                   int* index, std::vector<std::string> choices);

  const std::vector<Param>& all() const { return params_; }
  std::vector<Param>& all() { return params_; }
  Param* Find(const std::string& key);

  /// Parses `text` for the param and stores it. Returns an error message, empty on success
  /// (non-finite numbers, unknown choices and malformed values are errors).
  static std::string SetFromString(Param& p, const std::string& text);
  /// The current value as the text YAML would hold.
  static std::string ToString(const Param& p);

 private:
  std::vector<Param> params_;
};

/// Changes the UI asks for, applied by the loop between two steps (MuJoCo-simulate style), so a
/// slider never races the step.
struct PendingChanges {
  struct Edit {
    std::string key;
    std::string value;  ///< as text, parsed with ParamTable::SetFromString
  };
  std::vector<Edit> edits;
  bool reset = false;
  int single_steps = 0;
  /// Drag requests while paused: robot or obstacle name -> new world position.
  struct Move {
    std::string name;
    double x = 0, y = 0;
  };
  std::vector<Move> moves;
  bool empty() const { return edits.empty() && !reset && single_steps == 0 && moves.empty(); }
};

}  // namespace formsim::sim
