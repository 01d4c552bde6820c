#include "sim/core/recorder.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "control/common/shortest_double_format.hpp"
#include "sim/core/number_format.hpp"
#include "sim/core/thread_pool.hpp"

namespace formsim::sim {

namespace {
// Rows the background writer holds at most (the simulation waits when they are all taken).
constexpr std::size_t kWriterSlots = 8;

// The longest cell: a comma and the longest shortest form of a double
// ("-2.2250738585072014e-308", 24 characters).
constexpr std::size_t kMaxCell = 25;

// Cells [0, n) of a row and a newline, written at `out` (room for n * kMaxCell + 1 characters);
// returns the end. Each number is the shortest text that reads back to the same double (to_chars);
// not sampled: empty; NaN, ±infinity: nan, inf, -inf.
char* FormatRow(const double* v, std::size_t n, char* out) {
  for (std::size_t c = 0; c < n; ++c) {
    if (c) *out++ = ',';
    const double x = v[c];
    if (std::isfinite(x)) {
      out = control::WriteShortestDouble(out, out + kMaxCell, x);
    } else if (!IsNotSampled(x)) {
      const char* text = std::isnan(x) ? "nan" : x > 0 ? "inf" : "-inf";
      const std::size_t len = std::strlen(text);
      std::memcpy(out, text, len);
      out += len;
    }
  }
  *out++ = '\n';
  return out;
}

// A row's text in `buf` (grown to fit once; no per-cell appends to a string).
std::size_t FormatRowInto(const double* v, std::size_t n, std::vector<char>& buf) {
  if (buf.size() < n * kMaxCell + 1) buf.resize(n * kMaxCell + 1);
  return static_cast<std::size_t>(FormatRow(v, n, buf.data()) - buf.data());
}
}  // namespace

bool AllFiniteOrNotSampled(const double* v, std::size_t n) {
  // Usually every value is finite: Σ 0·v is 0 then, NaN when any value is infinite, NaN or
  // NotSampled(); only then are the bits looked at. Four sums, so that the additions overlap.
  double z[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t c = 0;
  for (; c + 4 <= n; c += 4)
    for (int k = 0; k < 4; ++k) z[k] += 0.0 * v[c + k];
  for (; c < n; ++c) z[0] += 0.0 * v[c];
  if ((z[0] + z[1]) + (z[2] + z[3]) == 0.0) return true;
  // Not finite: all exponent bits set (infinity or NaN).
  constexpr std::uint64_t kExponent = 0x7ff00000'00000000ULL;
  std::uint64_t bad = 0;
  for (c = 0; c < n; ++c) {
    std::uint64_t bits;
    std::memcpy(&bits, v + c, sizeof bits);
    bad |= static_cast<std::uint64_t>((bits & kExponent) == kExponent && bits != kNotSampledBits);
  }
  return bad == 0;
}

// Checked, buffered writing of one CSV file through a temporary name.
class Recorder::Stream {
 public:
  explicit Stream(const std::string& path) : path_(path), tmp_(path + ".tmp") {
    f_ = std::fopen(tmp_.c_str(), "wb");
    if (f_ == nullptr)
      throw std::runtime_error("cannot write '" + tmp_ + "': " + std::strerror(errno));
    std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
  }
  ~Stream() { Abandon(); }
  void Write(const std::string& text) { Write(text.data(), text.size()); }
  void Write(const char* text, std::size_t size) {
    if (failed_) return;
    if (std::fwrite(text, 1, size, f_) != size) Fail();
  }
  void Finish() {
    if (f_ == nullptr) return;
    if (!failed_ && std::fflush(f_) != 0) Fail();
    if (!failed_ && fsync(fileno(f_)) != 0) Fail();
    const bool closed = std::fclose(f_) == 0;
    f_ = nullptr;
    if (!closed && !failed_) failed_ = true, error_ = std::strerror(errno);
    if (failed_) {
      std::remove(tmp_.c_str());
      throw std::runtime_error("cannot write '" + path_ + "': " + error_);
    }
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
      const std::string why = std::strerror(errno);
      std::remove(tmp_.c_str());
      throw std::runtime_error("cannot move '" + tmp_ + "' to '" + path_ + "': " + why);
    }
  }
  void Abandon() {
    if (f_ == nullptr) return;
    std::fclose(f_);
    f_ = nullptr;
    std::remove(tmp_.c_str());
  }
  bool failed() const { return failed_; }
  const std::string& error() const { return error_; }

 private:
  void Fail() {
    failed_ = true;
    error_ = std::strerror(errno);
  }
  std::string path_, tmp_;
  std::FILE* f_ = nullptr;
  bool failed_ = false;
  std::string error_;
};

// The background writer: rows copied into a fixed ring of slots by Sample(), formatted and
// written in order by one thread. Allocates nothing per row once the slots and its line have
// grown.
class Recorder::Writer {
 public:
  Writer(Stream& stream, std::size_t columns) : stream_(stream), columns_(columns) {
    for (auto& slot : slots_) slot.resize(columns);
    thread_ = std::thread([this] { Loop(); });
  }
  ~Writer() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }
  // Copies a row into the next free slot (waiting for one when the writer is behind).
  void Push(const double* row) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return count_ < kWriterSlots; });
    std::copy(row, row + columns_, slots_[(head_ + count_) % kWriterSlots].begin());
    ++count_;
    lock.unlock();
    changed_.notify_all();
  }
  // Returns once every row pushed so far is written.
  void Drain() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return count_ == 0 && !busy_; });
  }

 private:
  void Loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      changed_.wait(lock, [&] { return count_ > 0 || stop_; });
      if (count_ == 0) return;  // stopping, nothing left
      const std::vector<double>& row = slots_[head_];
      busy_ = true;
      lock.unlock();
      // The length first: FormatRowInto may grow line_ (and move its data).
      const std::size_t length = FormatRowInto(row.data(), columns_, line_);
      stream_.Write(line_.data(), length);
      lock.lock();
      busy_ = false;
      head_ = (head_ + 1) % kWriterSlots;
      --count_;
      changed_.notify_all();
    }
  }

  Stream& stream_;
  std::size_t columns_;
  std::vector<double> slots_[kWriterSlots];
  std::size_t head_ = 0, count_ = 0;
  bool busy_ = false, stop_ = false;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<char> line_;
  std::thread thread_;
};

Recorder::Recorder() = default;
Recorder::~Recorder() {
  StopWriter();
}

int Recorder::Declare(const std::string& name) {
  if (rows_ > 0) throw std::logic_error("Recorder: column '" + name + "' declared after rows");
  const int column = static_cast<int>(names_.size());
  if (!index_.emplace(name, column).second)
    throw std::logic_error("Recorder: duplicate column '" + name + "'");
  names_.push_back(name);
  return column;
}

void Recorder::Add(const std::string& name, std::function<double()> get) {
  const int c = Declare(name);
  groups_.push_back({c, 1, [get = std::move(get)](double* out) { out[0] = get(); }});
}

void Recorder::AddGroup(const std::vector<std::string>& names,
                        std::function<void(double* out)> fill) {
  if (names.empty()) return;
  const int first = Declare(names[0]);
  for (std::size_t i = 1; i < names.size(); ++i) Declare(names[i]);
  groups_.push_back({first, static_cast<int>(names.size()), std::move(fill)});
}

int Recorder::Column(const std::string& name) const {
  const auto it = index_.find(name);
  return it == index_.end() ? -1 : it->second;
}

void Recorder::Sample() {
  const std::size_t n = names_.size();
  scratch_.assign(n, NotSampled());
  for (const Group& g : groups_) g.fill(&scratch_[g.first]);
  if (writer_) {
    writer_->Push(scratch_.data());
  } else if (stream_) {
    const std::size_t length = FormatRowInto(scratch_.data(), n, line_);  // may grow line_
    stream_->Write(line_.data(), length);
  }
  // The history keeps every stride-th sampled row; when full it drops every second row.
  if (sampled_++ % stride_ != 0) return;
  if (limit_ > 0 && rows_ >= limit_) {
    Unshare(data_->capacity());  // the rows are rewritten in place
    std::vector<double>& d = *data_;
    std::size_t kept = 0;
    for (std::size_t r = 0; r < rows_; r += 2, ++kept)
      std::copy(d.begin() + r * n, d.begin() + (r + 1) * n, d.begin() + kept * n);
    rows_ = kept;
    d.resize(rows_ * n);
    stride_ *= 2;
    if ((sampled_ - 1) % stride_ != 0) return;
  }
  if (data_->size() + n > data_->capacity()) {
    Grow();
    // Full and shared: a new buffer, as the vector's own doubling would make.
    if (data_->size() + n > data_->capacity())
      Unshare(std::max(2 * data_->capacity(), data_->size() + n));
  }
  data_->insert(data_->end(), scratch_.begin(), scratch_.end());
  ++rows_;
}

void Recorder::Unshare(std::size_t capacity) {
  if (data_.use_count() == 1) return;
  auto own = std::make_shared<std::vector<double>>();
  own->reserve(std::max(capacity, data_->size()));
  own->assign(data_->begin(), data_->end());
  data_ = std::move(own);
}

void Recorder::Grow() {
  constexpr std::size_t kMaxReserve = std::size_t{256} << 20;  // bytes
  const std::size_t n = names_.size();
  std::size_t rows = expected_rows_;
  if (limit_ > 0) rows = std::min(rows, limit_);
  // Beyond the expected rows, or too many to reserve at once: the vector's own doubling.
  if (rows <= rows_ || rows * n * sizeof(double) > kMaxReserve) return;
  if (data_.use_count() > 1)
    Unshare(rows * n);  // a reserve would move the rows a SharedRows() holder reads
  else
    data_->reserve(rows * n);
}

void Recorder::SetHistoryLimit(std::size_t max_rows) {
  limit_ = max_rows < 2 && max_rows > 0 ? 2 : max_rows;
}

void Recorder::AppendRow(std::string& line, std::size_t r) const {
  const std::size_t n = names_.size();
  const std::size_t at = line.size();
  line.resize(at + n * kMaxCell + 1);
  line.resize(
      static_cast<std::size_t>(FormatRow(&(*data_)[r * n], n, line.data() + at) - line.data()));
}

void Recorder::StreamTo(const std::string& path) {
  if (stride_ != 1) throw std::logic_error("Recorder::StreamTo after the history was decimated");
  StopWriter();
  stream_.reset();
  stream_ = std::make_unique<Stream>(path);
  stream_path_ = path;
  std::string text;
  for (std::size_t c = 0; c < names_.size(); ++c) text += (c ? "," : "") + names_[c];
  text += '\n';
  for (std::size_t r = 0; r < rows_; ++r) AppendRow(text, r);
  stream_->Write(text);
  if (stream_->failed()) {
    const std::string why = stream_->error();
    stream_.reset();
    throw std::runtime_error("cannot write '" + path + "': " + why);
  }
  if (pool_ != nullptr && pool_->threads() > 1)
    writer_ = std::make_unique<Writer>(*stream_, names_.size());
}

void Recorder::StopWriter() {
  if (!writer_) return;
  writer_->Drain();
  writer_.reset();
}

void Recorder::FinishStream() {
  StopWriter();
  if (!stream_) return;
  std::unique_ptr<Stream> s = std::move(stream_);
  s->Finish();
}

void Recorder::AbandonStream() {
  StopWriter();
  stream_.reset();
}

std::vector<double> Recorder::Series(int column) const {
  std::vector<double> out(rows_);
  for (std::size_t r = 0; r < rows_; ++r) out[r] = At(r, column);
  return out;
}

void Recorder::WriteCsv(const std::string& file) const {
  if (stride_ != 1)
    throw std::logic_error("Recorder::WriteCsv of a decimated history (stream long runs instead)");
  Stream out(file);
  std::string text;
  for (std::size_t c = 0; c < names_.size(); ++c) text += (c ? "," : "") + names_[c];
  text += '\n';
  for (std::size_t r = 0; r < rows_; ++r) {
    AppendRow(text, r);
    if (text.size() > (1u << 20)) {
      out.Write(text);
      text.clear();
    }
  }
  out.Write(text);
  out.Finish();
}

}  // namespace formsim::sim
