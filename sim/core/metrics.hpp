#pragma once
/// \file The results of a run, declared once: a tree of named values (dotted paths, e.g.
/// "links.R1-R2.max_abs_error_after_settle.phi") that is rendered as summary.json's `results`,
/// as the table `formsim run` prints, as the GUI's summary tables, and flattened into the
/// columns of a sweep's runs.csv under the same names.

#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "sim/core/figure_spec.hpp"
#include "sim/core/json.hpp"

namespace formsim::sim {

/// Which way a metric is better, for comparing runs (the GUI's pinned runs, history, Monte
/// Carlo): errors, RMS values and counts of collisions or faults are better lower.
enum class Better { kNone, kLower, kHigher };

/// True when `path` matches `pattern`, where '*' stands for any run of characters (dots too):
/// "links.*.rmse_after_settle.*" matches "links.R1-R2.rmse_after_settle.l".
bool PathMatches(const std::string& pattern, const std::string& path);

/// Whether a value is an outcome of the run or a setting it ran with (control_period,
/// settle_time): settings are kept apart from the metrics of sweeps (runs.csv's `settings.`
/// columns), are never ranked and are never a sweep's default metric.
enum class MetricRole { kResult, kSetting };

/// What a metric is, declared by its kind for the paths matching a pattern.
struct MetricInfo {
  /// A label with markup (subscripts `e_{l}`, Greek letters by name), without the unit; "{1}",
  /// "{2}" ... stand for what the pattern's first, second ... '*' matched ("link {1}").
  std::string label;
  std::string unit;  ///< "m", "rad", "m/s"; empty: a count or a ratio
  Better better = Better::kNone;
  MetricRole role = MetricRole::kResult;
  int headline = 0;  ///< 1 for the kind's first headline, 2 ...; 0: not a headline
  /// The label with the unit in brackets ("max|e_{l}| after settling, link R1-R2 [m]"), or
  /// `fallback` (the dotted path) when nothing is declared.
  std::string AxisLabel(const std::string& fallback) const;
};

/// What the '*' of `pattern` matched in `path` (in order), or false when it does not match.
bool PathCaptures(const std::string& pattern, const std::string& path,
                  std::vector<std::string>* captures);

class Metrics {
 public:
  /// A number at a dotted path (set again: replaced in place).
  void Set(const std::string& path, double value);
  /// A yes/no value (true/false in summary.json, 1/0 in sweep tables).
  void SetFlag(const std::string& path, bool value);
  /// A setting the run used (a number, as Set), marked MetricRole::kSetting.
  void SetSetting(const std::string& path, double value);
  /// A text value (a mode, an estimator name).
  void SetText(const std::string& path, const std::string& text);
  /// A line printed above the tables ("formation: bearing das, gains per sample").
  void AddNote(const std::string& line) { notes_.push_back(line); }

  /// A table view over the tree: one row per path prefix, one column per sub-path.
  struct Column {
    std::string header;
    std::string path;    ///< below the row's prefix, e.g. "max_abs_error_after_settle.l"
    std::string format;  ///< printf format for numbers ("%.3e"); empty: shortest round-trip
  };
  struct Table {
    std::string title;
    std::string row_header;                               ///< e.g. "link"
    std::vector<std::pair<std::string, std::string>> rows;  ///< label, path prefix ("links.R1-R2")
    std::vector<Column> columns;
  };
  void AddTable(Table table) { tables_.push_back(std::move(table)); }
  const std::vector<Table>& tables() const { return tables_; }

  /// Declares which way values at the paths matching `pattern` are better (later declarations
  /// win). Undeclared paths are kNone: shown, never ranked.
  void SetBetter(const std::string& pattern, Better better) {
    better_.emplace_back(pattern, better);
  }
  /// Which way the value at `path` is better.
  Better BetterOf(const std::string& path) const;

  /// Declares the label and unit (and, when given, the direction) of the paths matching
  /// `pattern`; later declarations win. The direction is also declared as by SetBetter.
  void Describe(const std::string& pattern, const std::string& label, const std::string& unit,
                Better better = Better::kNone);
  /// Everything declared about `path`: its label (captures substituted) and unit, direction,
  /// role and headline rank (the first headline whose pattern matches it).
  MetricInfo InfoOf(const std::string& path) const;

  /// A headline metric: the few numbers a run is judged by at a glance (a row of the GUI's run
  /// history). `pattern` names one path, or several with '*'; `combine` folds the matches.
  enum class Combine { kValue, kMax, kSum };
  struct Headline {
    std::string label;    ///< column title, e.g. "max|e_l| worst link [m]"
    std::string pattern;  ///< e.g. "links.*.max_abs_error_after_settle.l"
    Combine combine = Combine::kValue;
    std::string format;  ///< printf format ("%.3e"); empty: shortest round-trip
  };
  void AddHeadline(Headline h) { headlines_.push_back(std::move(h)); }
  /// The headline values (NaN when nothing matches), with their direction (the direction of the
  /// first matching path). Without declared headlines: the first three numbers of the tree.
  struct HeadlineValue {
    std::string label, format;
    double value = 0;
    Better better = Better::kNone;
  };
  std::vector<HeadlineValue> Headlines() const;

  /// `results` of summary.json: nested objects in the order the values were set.
  Json ToJson() const;
  /// The printed summary: notes, then each table as aligned text.
  std::string Text() const;
  /// The same tables for the GUI.
  std::vector<TableSpec> GuiTables() const;
  /// Every number with its dotted path, in the order set.
  std::vector<std::pair<std::string, double>> Scalars() const;
  /// The numbers of one role (results: what sweeps rank and plot; settings: what they ran with).
  std::vector<std::pair<std::string, double>> Scalars(MetricRole role) const;
  /// The value at `path` (a number), or nullptr.
  const double* Find(const std::string& path) const;
  /// A cell as text: the number with `format`, the text value, or "-" when absent.
  std::string Cell(const std::string& path, const std::string& format) const;

 private:
  struct Entry {
    std::string path;
    bool is_text = false;
    bool is_flag = false;
    bool is_setting = false;
    double value = 0.0;
    std::string text;
  };
  Entry* Slot(const std::string& path);
  const Entry* Lookup(const std::string& path) const;
  std::vector<Entry> entries_;
  std::unordered_map<std::string, std::size_t> index_;  ///< path -> entry, linear summaries
  std::vector<std::string> notes_;
  std::vector<Table> tables_;
  std::vector<std::pair<std::string, Better>> better_;
  struct Description {
    std::string pattern, label, unit;
  };
  std::vector<Description> descriptions_;
  std::vector<Headline> headlines_;
};

}  // namespace formsim::sim
