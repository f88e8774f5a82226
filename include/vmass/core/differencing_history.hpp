// DifferencingHistory: the last dt of tick records an extractor differences against (paper
// eqs. 5 and 9), with the checks both extractors need before a difference is meaningful:
// enough history (else kWarmingUp) and the record dt ago really dt ago in time (else kTimeGap,
// a hole in the data). Records need a `time_us` member. Allocates only in the constructor.
// Not thread-safe.
#pragma once

#include <cstdlib>

#include "vmass/core/delay_line.hpp"
#include "vmass/core/extraction.hpp"

namespace vmass {

template <typename Record>
class DifferencingHistory {
 public:
  explicit DifferencingHistory(const DifferencingParams& differencing)
      : steps_(static_cast<std::size_t>(differencing.steps())),
        expected_us_(from_seconds(differencing.differencing_dt_s)),
        tolerance_us_(from_seconds(0.5 / differencing.tick_rate_hz)),
        records_(steps_ + 1) {}

  /// Store `now` and return the record dt before it, or nullptr with *verdict set to
  /// kWarmingUp or kTimeGap.
  const Record* push_and_get_then(const Record& now, PairVerdict* verdict) {
    records_.push(now);
    if (records_.size() <= steps_) {
      *verdict = PairVerdict::kWarmingUp;
      return nullptr;
    }
    const Record& then = records_.ago(steps_);
    if (std::llabs((now.time_us - then.time_us) - expected_us_) > tolerance_us_) {
      *verdict = PairVerdict::kTimeGap;
      return nullptr;
    }
    return &then;
  }

  void clear() { records_.clear(); }

 private:
  std::size_t steps_;
  TimeUs expected_us_;
  TimeUs tolerance_us_;
  DelayLine<Record> records_;
};

}  // namespace vmass
