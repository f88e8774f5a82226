// TickDriver: plays a recording (an InputSource whose records carry their own times) through
// the tick grid, the one loop vmass-replay, vmass-calibrate --ballast LOG and vmassd --speed max
// run:
//
//   T_0 = the first record's time;  for k = 0, 1, ...:
//     the clock says when tick k may run (TickClock::wait_for_tick)
//     every record stamped at or before T_k is applied to the source's table (file order)
//     on_tick(k, T_k)
//   the last tick is the last T_k at or before the latest record's time.
//
// Records out of time order are applied when read (no tick is repeated). The clock is
// injected: UnpacedClock runs every tick at once (offline, `--speed max`); the daemon's clock
// also stops the run when asked to.
//
// Not thread-safe: one thread reads, applies and ticks. Allocates nothing per tick.
#pragma once

#include <cstdint>
#include <functional>

#include "vmass/runtime/input_source.hpp"
#include "vmass/runtime/tick_grid.hpp"

namespace vmass::runtime {

class TickClock {
 public:
  virtual ~TickClock() = default;
  /// Returns when tick k, at T_k on the input's clock, may run; false: stop before it.
  virtual bool wait_for_tick(std::int64_t k, TimeUs t_k) = 0;
};

/// Every tick at once: the run takes as long as the computation.
class UnpacedClock final : public TickClock {
 public:
  bool wait_for_tick(std::int64_t /*k*/, TimeUs /*t_k*/) override { return true; }
};

struct TickRun {
  std::int64_t ticks = 0;       ///< ticks run
  bool any_record = false;      ///< false: the recording is empty (no tick)
  TimeUs first_record_us = 0;   ///< T_0
  TimeUs latest_record_us = 0;  ///< the latest time of any record applied
  bool stopped = false;         ///< the clock stopped the run before the end
};

class TickDriver {
 public:
  using OnTick = std::function<void(std::int64_t k, TimeUs t_k)>;

  /// source must be a recording (InputSource::recorded()); tick_rate_hz > 0.
  TickDriver(InputSource& source, double tick_rate_hz);

  /// Plays the whole recording (see the header comment).
  TickRun run(TickClock& clock, const OnTick& on_tick);

 private:
  InputSource& source_;
  double tick_rate_hz_;
};

}  // namespace vmass::runtime
