#include "vmass/csv/tick_resampler.hpp"

namespace vmass {

TickResampler::TickResampler(double tick_rate_hz, double stale_after_s)
    : tick_us_(from_seconds(1.0 / tick_rate_hz)), stale_us_(from_seconds(stale_after_s)) {}

void TickResampler::push(const Sample& sample, const std::function<void(const Sample&)>& on_tick) {
  if (!started_) {
    started_ = true;
    next_tick_us_ = sample.time_us;
  }
  // Ticks strictly before this sample see the previously held one.
  while (next_tick_us_ < sample.time_us) {
    Sample tick = held_;
    if (next_tick_us_ - held_.time_us > stale_us_) tick.valid = 0;
    tick.time_us = next_tick_us_;
    on_tick(tick);
    next_tick_us_ += tick_us_;
  }
  held_ = sample;
  if (next_tick_us_ == sample.time_us) {
    on_tick(sample);
    next_tick_us_ += tick_us_;
  }
}

}  // namespace vmass
