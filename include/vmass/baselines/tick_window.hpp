// TickWindow: the last `steps` + 1 records of an uninterrupted run of ticks, so that a record can
// be differenced with the one exactly `steps` ticks (dt = steps / tick rate) before it. The caller
// clears it at every hole (see TickContinuity), so the window never spans one. Records need a
// `time_us` member. Allocates only in the constructor; not thread-safe.
#pragma once

#include <cstddef>
#include <vector>

namespace vmass::baselines {

template <typename Record>
class TickWindow {
 public:
  /// steps >= 1.
  explicit TickWindow(int steps)
      : steps_(static_cast<std::size_t>(steps < 1 ? 1 : steps)), records_(steps_ + 1) {}

  /// Store `now` and return the record `steps` ticks before it, or nullptr while the run since
  /// the last clear() is shorter than that.
  const Record* push(const Record& now) {
    records_[head_] = now;
    head_ = (head_ + 1) % records_.size();
    if (count_ < records_.size()) ++count_;
    if (count_ <= steps_) return nullptr;
    return &records_[head_];  // the oldest of steps + 1 records
  }

  void clear() {
    head_ = 0;
    count_ = 0;
  }
  std::size_t steps() const { return steps_; }

 private:
  std::size_t steps_;
  std::vector<Record> records_;
  std::size_t head_ = 0;   ///< where the next record goes
  std::size_t count_ = 0;  ///< records since clear(), capped at steps + 1
};

}  // namespace vmass::baselines
