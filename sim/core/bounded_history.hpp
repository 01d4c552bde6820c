#pragma once
/// \file A history of samples kept for figures and drawing (sensor fixes, trails) that stays
/// bounded however long the run: when full, every second sample is dropped and from then on
/// only every 2nd (4th, ...) new sample is kept, so the whole run stays covered evenly. The
/// same rule as the recorder's history.

#include <cstddef>
#include <vector>

namespace formsim::sim {

template <class T>
class BoundedHistory {
 public:
  explicit BoundedHistory(std::size_t limit = 20000) : limit_(limit < 2 ? 2 : limit) {}
  void push_back(const T& v) {
    if (seen_++ % stride_ != 0) return;
    if (items_.size() >= limit_) {
      std::size_t kept = 0;
      for (std::size_t i = 0; i < items_.size(); i += 2) items_[kept++] = items_[i];
      items_.resize(kept);
      stride_ *= 2;
      if ((seen_ - 1) % stride_ != 0) return;
    }
    items_.push_back(v);
  }
  std::size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }
  const T& operator[](std::size_t i) const { return items_[i]; }
  const T& back() const { return items_.back(); }
  typename std::vector<T>::const_iterator begin() const { return items_.begin(); }
  typename std::vector<T>::const_iterator end() const { return items_.end(); }
  /// The kept samples, oldest first.
  const std::vector<T>& items() const { return items_; }
  /// Samples offered so far (kept or not).
  std::size_t seen() const { return seen_; }

 private:
  std::vector<T> items_;
  std::size_t limit_;
  std::size_t stride_ = 1;
  std::size_t seen_ = 0;
};

}  // namespace formsim::sim
