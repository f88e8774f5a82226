// MassBaseline: one published mass estimator, fed the same ticks as vmass.
//
// step() takes one tick (at the tick rate given to make_baseline, time in sample.time_us). Inputs
// follow vmass::Sample: SI units, ISO 8855, a validity bit per input. Every baseline skips invalid
// or non-finite inputs and never differences or filters across a hole in the data (an input it
// needs invalid or non-finite, or a tick not exactly one period after the previous one): its
// pipeline restarts after the hole. Ticks where its model does not hold (braking for some) are
// left out as each header says. Not thread-safe; no allocation after construction.
#pragma once

#include <string_view>

#include "vmass/baselines/baseline_estimate.hpp"
#include "vmass/core/sample.hpp"

namespace vmass::baselines {

class MassBaseline {
 public:
  virtual ~MassBaseline() = default;
  /// One tick.
  virtual void step(const vmass::Sample& sample) = 0;
  virtual BaselineEstimate estimate() const = 0;
  /// "paper", "paper_lp", "vahidi2005" or "fathy2008".
  virtual std::string_view name() const = 0;
};

}  // namespace vmass::baselines
