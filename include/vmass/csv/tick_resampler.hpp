// TickResampler: turns samples that arrive at their own times into one Sample per estimator
// tick (zero-order hold), the way the daemon's fixed-rate loop sees its signal table. A held
// sample older than stale_after_s makes every input invalid at that tick.
// Not thread-safe.
#pragma once

#include <functional>

#include "vmass/core/sample.hpp"

namespace vmass {

class TickResampler {
 public:
  TickResampler(double tick_rate_hz, double stale_after_s);

  /// Feed the next sample (increasing times); calls on_tick for every tick up to and including
  /// the sample's time.
  void push(const Sample& sample, const std::function<void(const Sample&)>& on_tick);

 private:
  TimeUs tick_us_;
  TimeUs stale_us_;
  bool started_ = false;
  TimeUs next_tick_us_ = 0;
  Sample held_;
};

}  // namespace vmass
