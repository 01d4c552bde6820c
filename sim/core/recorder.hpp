#pragma once
/// \file Time-series recording: experiments declare named columns once and append one row per
/// recorded step. The CSV writer, the exported figures and the live GUI plots all read this.

#include <cstddef>
#include <string>
#include <unordered_map>
#include <vector>

namespace formsim::sim {

class Recorder {
 public:
  /// Declares a column and returns its index. All columns must be declared before the first row.
  int AddColumn(const std::string& name);
  int Column(const std::string& name) const;  ///< -1 when absent
  /// Starts a row (values default to NaN), set values with Set, the row ends at the next Begin.
  void BeginRow();
  void Set(int column, double value);
  void Clear();

  std::size_t rows() const { return rows_; }
  std::size_t columns() const { return names_.size(); }
  const std::vector<std::string>& names() const { return names_; }
  double At(std::size_t row, int column) const { return data_[row * names_.size() + column]; }
  /// Copies one column out.
  std::vector<double> Series(int column) const;

  /// Writes CSV with a header; each number as the shortest text that reads back to the same
  /// double, so runs compare bit for bit. Unsampled (NaN) cells are empty.
  /// Throws std::runtime_error naming the file when it cannot be written.
  void WriteCsv(const std::string& file) const;

 private:
  std::vector<std::string> names_;
  std::unordered_map<std::string, int> index_;  ///< name -> column, so setup stays linear
  std::vector<double> data_;
  std::size_t rows_ = 0;
};

}  // namespace formsim::sim
