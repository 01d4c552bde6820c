#pragma once
/// \file Time-series recording. An experiment declares each channel once, with the code that
/// reads its value (`rec.Add("R1.v_cmd", [this] { return cmd_.v; })`); every recorded step
/// samples all channels into one row. The CSV writer, the exported figures and the live GUI
/// plots all read these rows.

#include <cstddef>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

namespace formsim::sim {

/// The value a channel returns when it has nothing to say in this row (an empty CSV cell). A
/// NaN with its own payload, so that a NaN that was computed stays visible as `nan`.
double NotSampled();
/// True for exactly the NotSampled() bit pattern.
bool IsNotSampled(double v);

class Recorder {
 public:
  /// Declares a channel: its column name and how to read it (NotSampled() when it has no value
  /// in this row). All channels are declared before the first row.
  void Add(const std::string& name, std::function<double()> get);
  /// Declares several columns filled by one call (e.g. x, y, θ of one pose): `fill` writes
  /// names.size() values into `out`.
  void AddGroup(const std::vector<std::string>& names, std::function<void(double* out)> fill);
  /// Samples every channel into a new row.
  void Sample();
  void Clear();

  int Column(const std::string& name) const;  ///< -1 when absent
  std::size_t rows() const { return rows_; }
  std::size_t columns() const { return names_.size(); }
  const std::vector<std::string>& names() const { return names_; }
  double At(std::size_t row, int column) const { return data_[row * names_.size() + column]; }
  /// Copies one column out.
  std::vector<double> Series(int column) const;

  /// Writes CSV with a header; each number as the shortest text that reads back to the same
  /// double, so runs compare bit for bit. NotSampled() cells are empty; NaN or infinite values
  /// that were computed are written as nan / inf / -inf. Throws std::runtime_error naming the
  /// file when it cannot be written completely.
  void WriteCsv(const std::string& file) const;

 private:
  int Declare(const std::string& name);
  struct Group {
    int first = 0, count = 1;
    std::function<void(double*)> fill;
  };
  std::vector<std::string> names_;
  std::unordered_map<std::string, int> index_;  ///< name -> column, so setup stays linear
  std::vector<Group> groups_;
  std::vector<double> data_;
  std::size_t rows_ = 0;
};

}  // namespace formsim::sim
