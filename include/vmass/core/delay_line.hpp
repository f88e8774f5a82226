// DelayLine: a fixed-capacity ring buffer of the last N tick records, so that an extractor can
// difference "now" against "dt ago" (paper eqs. 5 and 9). Capacity is set at construction; push
// never allocates. Not thread-safe.
#pragma once

#include <cstddef>
#include <vector>

namespace vmass {

template <typename T>
class DelayLine {
 public:
  explicit DelayLine(std::size_t capacity) : items_(capacity == 0 ? 1 : capacity) {}

  void push(const T& item) {
    head_ = (head_ + 1) % items_.size();
    items_[head_] = item;
    if (size_ < items_.size()) ++size_;
  }
  void clear() { size_ = 0; }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return items_.size(); }
  /// The item pushed `age` pushes ago (0 = newest); requires age < size().
  const T& ago(std::size_t age) const {
    return items_[(head_ + items_.size() - age) % items_.size()];
  }

 private:
  std::vector<T> items_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace vmass
