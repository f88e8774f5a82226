#include "vmass/service/estimator_loop.hpp"

#include <type_traits>

namespace vmass::service {

static_assert(std::is_trivially_copyable<TickRecord>::value, "TickRecord goes through SpscQueue");

EstimatorLoop::EstimatorLoop(const PipelineParams& params, const InputTimeouts& timeouts)
    : pipeline_(params), timeouts_(timeouts) {}

const TickRecord& EstimatorLoop::tick(std::int64_t tick, TimeUs tick_us,
                                      const InputValues& values) {
  const Sample sample = sample_at(values, tick_us, timeouts_);
  const StepResult result = pipeline_.step(sample);
  record_.tick = tick;
  record_.estimate = pipeline_.estimate();
  record_.events = result.events;
  record_.estimate_changed = result.estimate_changed;
  record_.inputs_valid = sample.valid;
  for (int i = 0; i < kInputCount; ++i) {
    const TimeUs t = values.input_time_us[i];
    record_.input_age_s[i] = t < 0 ? -1.0 : to_seconds(tick_us - t);
  }
  return record_;
}

}  // namespace vmass::service
