// replay_candump: a candump -l log through a SignalTable, ticked in log time, the way
// vmass-replay --log and vmass-calibrate read CAN recordings.
//
//   t0 = time of the first frame;  tick k at  t_k = t0 + round(k * 1e6 / tick_rate_hz) us
//   every frame stamped at or before t_k is applied before tick k's Sample = sample_at(t_k);
//   ticks continue up to the last frame's time.
// Frames out of time order are applied when read (no tick is repeated). Corrupt lines are the
// reader's business: counted, reported through its on_error callback, skipped.
//
// Not thread-safe (one reader, one table).
#pragma once

#include <cstdint>
#include <functional>

#include "vmass/can/candump.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/signals/signal_table.hpp"

namespace vmass::signals {

struct LogReplayStats {
  std::int64_t ticks = 0;
  TimeUs first_frame_us = 0;  ///< t0 (0 when the log has no frame)
  TimeUs last_frame_us = 0;
  bool any_frame = false;
};

/// Feeds every frame of `reader` to `table` and calls on_tick(sample) at each tick.
LogReplayStats replay_candump(can::CandumpReader& reader, SignalTable& table, double tick_rate_hz,
                              const std::function<void(const Sample&)>& on_tick);

}  // namespace vmass::signals
