#include "vmass/signals/log_replay.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::signals {

LogReplayStats replay_candump(can::CandumpReader& reader, SignalTable& table, double tick_rate_hz,
                              const std::function<void(const Sample&)>& on_tick) {
  LogReplayStats stats;
  const double tick_us = 1e6 / tick_rate_hz;
  auto tick_time = [&](std::int64_t k) {
    return stats.first_frame_us +
           static_cast<TimeUs>(std::llround(static_cast<double>(k) * tick_us));
  };
  can::CandumpRecord record;
  while (reader.next(&record)) {
    const can::CanFrame& frame = record.frame;
    if (!stats.any_frame) {
      stats.any_frame = true;
      stats.first_frame_us = frame.time_us;
      stats.last_frame_us = frame.time_us;
    }
    while (tick_time(stats.ticks) < frame.time_us) {
      on_tick(table.sample_at(tick_time(stats.ticks)));
      ++stats.ticks;
    }
    table.on_frame(frame, frame.time_us);
    stats.last_frame_us = std::max(stats.last_frame_us, frame.time_us);
  }
  if (stats.any_frame) {
    while (tick_time(stats.ticks) <= stats.last_frame_us) {
      on_tick(table.sample_at(tick_time(stats.ticks)));
      ++stats.ticks;
    }
  }
  return stats;
}

}  // namespace vmass::signals
