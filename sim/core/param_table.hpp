#pragma once
/// \file Tunables: one declaration per value. A scenario reader declares each tunable where it
/// reads it (`YamlReader::Real("k_l", 0.15, Tune("k l").Above(0).Slider(1e-3, 1, kLog))`); that
/// one declaration carries the key (the YAML path, also the `--set` and GUI key), the default,
/// the hard validity the loader enforces, the slider range, the unit, the enum names and whether
/// an edit applies live or on reset. Reading a scenario fills a ParamTable with every tunable
/// and its current value; the GUI panel, `--set`, edit validation, Apply and Save all read it.

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

namespace formsim::sim {

/// Slider scale flag for Tune::Slider.
constexpr bool kLog = true;
/// The largest magnitude a slider end takes (Param::slider_min/max). A value beyond it (a
/// tunable left unbounded, edited to 1e308) is shown in a text field, not a slider: ImGui
/// asserts on slider ranges beyond half the largest double or float.
constexpr double kSliderLimit = 1e15;

/// The declaration of one tunable: label, unit, group, validity and slider. Built with chained
/// setters at the reader's call site, e.g.
///   Tune("control point L", "m").Above(0).Slider(0.05, 0.5).Group("Gains")
class Tune {
 public:
  Tune() = default;
  explicit Tune(std::string label, std::string unit = "") : label(std::move(label)), unit(std::move(unit)) {}

  /// GUI grouping "Head/Sub" (e.g. "Gains/R2"): a collapsing header and a tree node.
  Tune& Group(std::string g) { group = std::move(g); return *this; }
  /// Validity (the loader refuses anything else): v > x, v >= x, v < x, v <= x, lo <= v <= hi.
  Tune& Above(double x) { lo = x; lo_open = true; return *this; }
  Tune& AtLeast(double x) { lo = x; lo_open = false; return *this; }
  Tune& Below(double x) { hi = x; hi_open = true; return *this; }
  Tune& AtMost(double x) { hi = x; hi_open = false; return *this; }
  Tune& In(double a, double b) { return AtLeast(a).AtMost(b); }
  /// Slider range offered by the GUI; must lie inside the validity (checked when declared).
  Tune& Slider(double a, double b, bool log = false) { slider_lo = a; slider_hi = b; log_scale = log; return *this; }
  /// The value takes effect on the next reset, not between two steps.
  Tune& OnReset() { live = false; return *this; }
  /// A longer explanation for the GUI tooltip.
  Tune& Help(std::string h) { help = std::move(h); return *this; }

  /// "" when v is valid, else the reason ("must be > 0", "must be in [0, 1]").
  std::string Check(double v) const;
  /// The validity as text for messages and tooltips: "> 0", "[0, 1]", "any".
  std::string ValidityText() const;
  /// Throws std::logic_error when the slider range leaves the validity (a programming error).
  void CheckDeclaration(const std::string& key) const;

  std::string label, unit, group, help;
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  double slider_lo = std::numeric_limits<double>::quiet_NaN();
  double slider_hi = std::numeric_limits<double>::quiet_NaN();
  bool log_scale = false;
  bool live = true;
};

/// One tunable of a loaded scenario: its declaration and its current value.
struct Param {
  enum class Kind { kDouble, kInt, kBool, kChoice };
  std::string key;  ///< full YAML path: "robots.R2.follow.k_l" (list items by name or index)
  Kind kind = Kind::kDouble;
  Tune tune;
  std::vector<std::string> choices;  ///< kChoice: the YAML strings
  double value = 0.0;  ///< kDouble value, kInt value, kBool 0/1, kChoice index
  bool in_file = false;  ///< the key is written in the scenario (else the default applies)

  /// Slider range: the declared one, or a range derived from the validity and the value;
  /// always finite and within ±kSliderLimit.
  double slider_min() const;
  double slider_max() const;
  /// The value as YAML text: shortest round-trip number, true/false, or the choice's name.
  std::string Text() const;
  /// Parses and checks `text` for this parameter (kind, finiteness, validity, choice names).
  /// Returns "" and sets *canonical to the normalised text, or returns the reason.
  std::string Parse(const std::string& text, std::string* canonical) const;
};

/// Every tunable of a scenario, in declaration order (the GUI shows them in this order).
class ParamTable {
 public:
  void Add(Param p);
  const std::vector<Param>& all() const { return params_; }
  const Param* Find(const std::string& key) const;
  bool empty() const { return params_.empty(); }
  std::size_t size() const { return params_.size(); }
  /// A number no other content of any table has had in this process: each Add draws a new one
  /// (copies keep it), so two equal revisions mean the same parameters, and a view built from
  /// the table (the GUI's groups) stays valid while it holds. 0 for a table never added to.
  std::uint64_t revision() const { return revision_; }

 private:
  std::vector<Param> params_;
  std::uint64_t revision_ = 0;
  std::unordered_map<std::string, std::size_t> index_;  ///< key -> params_, so loading is linear
};

}  // namespace formsim::sim
