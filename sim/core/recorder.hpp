#pragma once
/// \file Time-series recording. An experiment declares each channel once, with the code that
/// reads its value (`rec.Add("R1.v_cmd", [this] { return cmd_.v; })`); every recorded step
/// samples all channels into one row. The CSV writer, the exported figures and the live GUI
/// plots all read these rows.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace formsim::sim {

class ThreadPool;

/// Bits of NotSampled(): a quiet NaN with its own payload.
constexpr std::uint64_t kNotSampledBits = 0x7ff80000'5e1f0001ULL;
/// The value a channel returns when it has nothing to say in this row (an empty CSV cell). A
/// NaN with its own payload, so that a NaN that was computed stays visible as `nan`.
inline double NotSampled() {
  double v;
  std::memcpy(&v, &kNotSampledBits, sizeof v);
  return v;
}
/// True for exactly the NotSampled() bit pattern.
inline bool IsNotSampled(double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof v);
  return bits == kNotSampledBits;
}
/// True when every value of v[0, n) is finite or NotSampled() (one branch-free pass).
bool AllFiniteOrNotSampled(const double* v, std::size_t n);

class Recorder {
 public:
  Recorder();
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  /// Declares a channel: its column name and how to read it (NotSampled() when it has no value
  /// in this row). All channels are declared before the first row.
  void Add(const std::string& name, std::function<double()> get);
  /// Declares several columns filled by one call (e.g. x, y, θ of one pose): `fill` writes
  /// names.size() values into `out`.
  void AddGroup(const std::vector<std::string>& names, std::function<void(double* out)> fill);
  /// Samples every channel into a new row (streamed to disk when StreamTo is on). Allocates
  /// nothing once the buffers have grown (the history grows until its limit).
  void Sample();
  /// With a pool of more than one thread, streamed rows are formatted and written by a
  /// background thread of the recorder's own (the simulation only copies each row into a
  /// slot), so the text of tens of thousands of columns fills the time a step leaves a core
  /// idle; the bytes are the same. nullptr or one thread: on the caller's thread. Takes effect
  /// at the next StreamTo.
  void SetPool(ThreadPool* pool) { pool_ = pool; }

  /// Streams every row to `path` as it is sampled (rows already recorded first), through
  /// `path`.tmp: FinishStream() flushes, syncs and renames it into place. So a run of any
  /// length writes its CSV as it goes. Throws std::runtime_error when the file cannot be
  /// opened or written (the temporary is removed).
  void StreamTo(const std::string& path);
  /// Completes the streamed file. Throws std::runtime_error (and removes the temporary) when
  /// any write failed.
  void FinishStream();
  /// Drops the streamed file (its temporary), e.g. when the run is abandoned.
  void AbandonStream();
  bool streaming() const { return stream_ != nullptr; }
  /// Keeps at most `max_rows` rows in memory for figures and live plots: when the limit is
  /// reached every second row is dropped and from then on only every 2nd (4th, ...) sampled
  /// row is kept, so memory stays bounded however long the run. 0: keep every row (default).
  void SetHistoryLimit(std::size_t max_rows);
  /// The row sampled last, whether the history kept it or not (for checks on every row).
  const std::vector<double>& last_sample() const { return scratch_; }
  /// The rows the run will sample (its duration over the recording interval): the history
  /// makes room for them (at most the history limit, at most 256 MB) when it first grows, so
  /// it is neither copied as it grows nor its pages touched twice.
  void ExpectRows(std::size_t rows) { expected_rows_ = rows; }
  /// Rows sampled since the start (kept in memory or not).
  std::size_t rows_sampled() const { return sampled_; }
  /// 1 while every sampled row is in memory; 2, 4, ... after decimation.
  std::size_t history_stride() const { return stride_; }

  int Column(const std::string& name) const;  ///< -1 when absent
  /// Rows kept in memory (all of them unless SetHistoryLimit decimated the history).
  std::size_t rows() const { return rows_; }
  std::size_t columns() const { return names_.size(); }
  const std::vector<std::string>& names() const { return names_; }
  double At(std::size_t row, int column) const { return (*data_)[row * names_.size() + column]; }
  /// The rows in memory, rows() x columns() row-major, as a buffer shared with the caller that
  /// stays valid and unchanged however the recording goes on: a row that needs more room, or a
  /// decimation, moves the history to a new buffer instead of changing this one, and the buffer
  /// outlives the recorder. (The Python module hands these rows out as numpy views.)
  std::shared_ptr<const std::vector<double>> SharedRows() const { return data_; }
  /// Copies one column out.
  std::vector<double> Series(int column) const;

  /// Writes the rows in memory as CSV with a header; each number as the shortest text that
  /// reads back to the same double, so runs compare bit for bit. NotSampled() cells are empty;
  /// NaN or infinite values that were computed are written as nan / inf / -inf. Throws
  /// std::runtime_error naming the file when it cannot be written completely (and leaves no
  /// partial file). Refuses a decimated history (use StreamTo for long runs).
  void WriteCsv(const std::string& file) const;

 private:
  class Stream;
  class Writer;
  int Declare(const std::string& name);
  void AppendRow(std::string& line, std::size_t row) const;
  /// Stops the background writer after it wrote every row handed to it.
  void StopWriter();
  /// Room for one more row of history (see ExpectRows).
  void Grow();
  /// Moves the history to a buffer of its own with room for `capacity` values, when a
  /// SharedRows() holder still reads the current one (copy on write).
  void Unshare(std::size_t capacity);
  struct Group {
    int first = 0, count = 1;
    std::function<void(double*)> fill;
  };
  std::vector<std::string> names_;
  std::unordered_map<std::string, int> index_;  ///< name -> column, so setup stays linear
  std::vector<Group> groups_;
  std::shared_ptr<std::vector<double>> data_ = std::make_shared<std::vector<double>>();
  std::size_t rows_ = 0;
  std::size_t sampled_ = 0;
  std::size_t limit_ = 0;          ///< rows kept in memory at most (0: all)
  std::size_t stride_ = 1;         ///< keep every stride-th sampled row
  std::size_t expected_rows_ = 0;  ///< see ExpectRows
  std::vector<double> scratch_;    ///< the row being sampled
  std::vector<char> line_;         ///< its text when streaming on the caller's thread
  ThreadPool* pool_ = nullptr;
  std::unique_ptr<Stream> stream_;
  std::unique_ptr<Writer> writer_;  ///< formats and writes streamed rows in the background
  std::string stream_path_;
};

}  // namespace formsim::sim
