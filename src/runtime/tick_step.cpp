#include "vmass/runtime/tick_step.hpp"

#include <type_traits>

namespace vmass::runtime {

static_assert(std::is_trivially_copyable<TickRecord>::value, "TickRecord goes through SpscQueue");

TickStep::TickStep(const PipelineParams& params) : pipeline_(params) {}

const TickRecord& TickStep::tick(std::int64_t tick, TimeUs tick_us, InputSource& source) {
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

}  // namespace vmass::runtime
