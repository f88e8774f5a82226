#include "vmass/runtime/input_source.hpp"

#include <algorithm>
#include <cstring>

namespace vmass::runtime {

Sample sample_at(const InputValues& values, TimeUs tick_us, const InputTimeouts& timeouts) {
  Sample s = values.latest;
  s.time_us = tick_us;
  for (int i = 0; i < kInputCount; ++i) {
    const InputMask bit = input_bit(static_cast<Input>(i));
    if ((s.valid & bit) == 0) continue;
    const TimeUs t = values.input_time_us[i];
    if (t == signals::kNeverUs || tick_us - t > timeouts.timeout_us[i]) s.valid &= ~bit;
  }
  return s;
}

void InputSource::set_health(SourceState state, const std::string& detail) {
  if (state == last_state_ && detail == last_detail_) return;  // no write when nothing changed
  last_state_ = state;
  last_detail_ = detail;
  SourceHealth h;
  h.state = state;
  const std::size_t n = std::min(detail.size(), sizeof(h.detail) - 1);
  std::memcpy(h.detail, detail.data(), n);
  h.detail[n] = '\0';
  health_.write(h);
}

void InputSource::publish_clock_counters(const ClockCounters& c) {
  counters_.reordered.store(c.reordered, std::memory_order_relaxed);
  counters_.late_dropped.store(c.late_dropped, std::memory_order_relaxed);
  counters_.time_jumps.store(c.time_jumps, std::memory_order_relaxed);
}

std::string_view source_state_name(SourceState s) {
  switch (s) {
    case SourceState::kOk:
      return "ok";
    case SourceState::kDown:
      return "input_lost";
    case SourceState::kEnded:
      return "input_ended";
  }
  return "unknown";
}

}  // namespace vmass::runtime
