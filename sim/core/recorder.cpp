#include "sim/core/recorder.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <stdexcept>

#include "sim/core/number_format.hpp"

namespace formsim::sim {

namespace {
constexpr std::uint64_t kNotSampledBits = 0x7ff80000'5e1f0001ULL;  // quiet NaN, own payload
}  // namespace

double NotSampled() {
  double v;
  std::memcpy(&v, &kNotSampledBits, sizeof v);
  return v;
}

bool IsNotSampled(double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof v);
  return bits == kNotSampledBits;
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
  const std::size_t base = data_.size();
  data_.resize(base + names_.size(), NotSampled());
  for (const Group& g : groups_) g.fill(&data_[base + g.first]);
  ++rows_;
}

void Recorder::Clear() {
  data_.clear();
  rows_ = 0;
}

std::vector<double> Recorder::Series(int column) const {
  std::vector<double> out(rows_);
  for (std::size_t r = 0; r < rows_; ++r) out[r] = At(r, column);
  return out;
}

void Recorder::WriteCsv(const std::string& file) const {
  std::FILE* f = std::fopen(file.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write '" + file + "'");
  std::string line;
  bool ok = true;
  for (std::size_t c = 0; c < names_.size(); ++c) {
    if (c) line += ',';
    line += names_[c];
  }
  line += '\n';
  ok = ok && std::fputs(line.c_str(), f) >= 0;
  for (std::size_t r = 0; r < rows_ && ok; ++r) {
    line.clear();
    for (std::size_t c = 0; c < names_.size(); ++c) {
      if (c) line += ',';
      const double v = data_[r * names_.size() + c];
      if (!IsNotSampled(v)) AppendDouble(line, v);  // not sampled -> empty field
    }
    line += '\n';
    ok = std::fputs(line.c_str(), f) >= 0;
  }
  ok = std::fflush(f) == 0 && ok;
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("error writing '" + file + "'");
}

}  // namespace formsim::sim
