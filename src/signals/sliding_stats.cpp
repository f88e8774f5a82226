#include "vmass/signals/sliding_stats.hpp"

#include <cmath>

namespace vmass::signals {

void RunningSum::add(double x) {
  const double sum = high_ + x;
  const double x_part = sum - high_;  // TwoSum: sum + rounding is high_ + x exactly
  const double rounding = (high_ - (sum - x_part)) + (x - x_part);
  high_ = sum;
  low_ += rounding;
}

bool RunningSum::finite() const { return std::isfinite(high_) && std::isfinite(low_); }

void SlidingSpread::clear() {
  largest_.clear();
  smallest_.clear();
}

void SlidingSpread::push(std::int64_t seq, double value) {
  largest_.push(seq, value);
  smallest_.push(seq, -value);
}

void SlidingSpread::drop_before(std::int64_t seq) {
  largest_.drop_before(seq);
  smallest_.drop_before(seq);
}

void SlidingSpread::MaxQueue::push(std::int64_t seq, double value) {
  while (size_ > 0 && at(size_ - 1).value <= value) --size_;  // can no longer be the largest
  at(size_) = Entry{seq, value};
  ++size_;
}

void SlidingSpread::MaxQueue::drop_before(std::int64_t seq) {
  while (size_ > 0 && entries_[front_].seq < seq) {
    front_ = (front_ + 1) & mask_;
    --size_;
  }
}

}  // namespace vmass::signals
