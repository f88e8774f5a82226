#include "vmass/service/estimator_loop.hpp"

#include <type_traits>

namespace vmass::service {

static_assert(std::is_trivially_copyable<TickRecord>::value, "TickRecord goes through SpscQueue");

EstimatorLoop::EstimatorLoop(const PipelineParams& params) : pipeline_(params) {}

const TickRecord& EstimatorLoop::tick(std::int64_t tick, TimeUs tick_us, InputSource& source) {
  const Sample sample = source.sample_at(tick_us);
  const StepResult result = pipeline_.step(sample);
  record_.tick = tick;
  record_.estimate = pipeline_.estimate();
  record_.events = result.events;
  record_.estimate_changed = result.estimate_changed;
  record_.inputs_valid = sample.valid;
  for (int i = 0; i < kInputCount; ++i) {
    const TimeUs age = source.input_age_us(static_cast<Input>(i), tick_us);
    record_.input_age_s[i] = age < 0 ? -1.0 : to_seconds(age);
  }
  return record_;
}

}  // namespace vmass::service
