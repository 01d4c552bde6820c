#pragma once
/// \file A fixed-capacity ring buffer: pushing into a full buffer drops the oldest element and
/// never allocates (trails of robots pushed every few steps of a long run).

#include <cstddef>
#include <vector>

namespace formsim::sim {

template <class T>
class RingBuffer {
 public:
  explicit RingBuffer(std::size_t capacity = 0) { SetCapacity(capacity); }
  /// Empties the buffer and sets its capacity (allocates once).
  void SetCapacity(std::size_t capacity) {
    data_.assign(capacity, T{});
    head_ = size_ = 0;
  }
  std::size_t capacity() const { return data_.size(); }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  /// Appends `v`, dropping the oldest element when full (nothing when the capacity is 0).
  void Push(const T& v) {
    if (!data_.empty()) PushSlot() = v;
  }
  /// The slot of a new newest element (the oldest one's when full) to be assigned in place, so
  /// that its members keep their storage. The capacity must be above 0.
  T& PushSlot() {
    T& slot = data_[(head_ + size_) % data_.size()];
    if (size_ < data_.size())
      ++size_;
    else
      head_ = (head_ + 1) % data_.size();
    return slot;
  }
  /// The i-th element, oldest first.
  const T& operator[](std::size_t i) const { return data_[(head_ + i) % data_.size()]; }
  /// Calls `f(first, count)` for the elements [from, size()), oldest first, as at most two
  /// contiguous runs (no index arithmetic per element: a thousand robots' trails each frame).
  template <class F>
  void ForEachRun(std::size_t from, F&& f) const {
    if (from >= size_) return;
    const std::size_t cap = data_.size(), start = (head_ + from) % cap, n = size_ - from;
    const std::size_t first = n < cap - start ? n : cap - start;
    f(data_.data() + start, first);
    if (first < n) f(data_.data(), n - first);
  }
  /// Appends the elements [from, size()) to `out`, oldest first.
  void AppendTo(std::vector<T>& out, std::size_t from = 0) const {
    ForEachRun(from, [&](const T* p, std::size_t n) { out.insert(out.end(), p, p + n); });
  }
  /// The newest element; the buffer must not be empty.
  const T& back() const { return (*this)[size_ - 1]; }

 private:
  std::vector<T> data_;
  std::size_t head_ = 0, size_ = 0;
};

}  // namespace formsim::sim
