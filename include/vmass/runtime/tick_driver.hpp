// TickDriver: the one tick loop of every front end: vmass-replay, vmass-calibrate --ballast LOG,
// and vmassd at every pace (--speed max, a paced replay, a live bus):
//
//   T_k on the TickGrid (T_0: the first record's time for a recording read here, else given)
//   for k = 0, 1, ...:
//     the clock says when tick k may run (TickClock::wait_for_tick)
//     every record stamped at or before T_k is applied to the source's table, in feed order
//       (a recording read by another thread: the tick waits until they have all come)
//     on_tick(k, T_k)
//     the clock says which tick is next (a live clock may give missed ticks up)
//   the last tick is the last T_k at or before the latest record's time, once the feed ended.
//
// Records out of time order are applied when read (no tick is repeated); a record stamped at or
// before the previous tick's time is counted as late. The clock and the feed are injected:
// UnpacedClock and SourceFeed offline (every tick at once, as fast as the computation); the
// daemon's monotonic clock and a RingFeed from its receive thread.
//
// Not thread-safe: one thread applies and ticks. Allocates nothing per tick.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "vmass/runtime/input_source.hpp"
#include "vmass/runtime/record_feed.hpp"
#include "vmass/runtime/tick_grid.hpp"

namespace vmass::runtime {

class TickClock {
 public:
  virtual ~TickClock() = default;
  /// Returns when tick k, at T_k on the input's clock, may run; false: stop before it.
  virtual bool wait_for_tick(std::int64_t k, TimeUs t_k) = 0;
  /// After tick k ran: the next tick to run (k + 1, or later to give missed ticks up).
  virtual std::int64_t next_tick(std::int64_t k) { return k + 1; }
};

/// Every tick at once: the run takes as long as the computation.
class UnpacedClock final : public TickClock {
 public:
  bool wait_for_tick(std::int64_t /*k*/, TimeUs /*t_k*/) override { return true; }
};

struct TickRun {
  std::int64_t ticks = 0;         ///< ticks passed: the last tick run + 1 (given-up ones count)
  bool any_record = false;        ///< false: no record was applied (an empty recording)
  TimeUs first_record_us = 0;     ///< T_0
  TimeUs latest_record_us = 0;    ///< the latest time of any record applied
  std::int64_t late_records = 0;  ///< stamped at or before the previous tick's time
  bool stopped = false;           ///< the clock stopped the run before the end
};

class TickDriver {
 public:
  using OnTick = std::function<void(std::int64_t k, TimeUs t_k)>;

  /// A recording read here (InputSource::recorded()), from its first record; tick_rate_hz > 0.
  TickDriver(InputSource& source, double tick_rate_hz);
  /// Records from `feed` into `table`'s input table, on `grid`.
  TickDriver(InputSource& table, RecordFeed& feed, const TickGrid& grid);

  /// Plays the feed to its end, or until the clock stops (see the header comment).
  TickRun run(TickClock& clock, const OnTick& on_tick);
  /// The run so far (from on_tick: the daemon's status reads the late records).
  const TickRun& progress() const { return run_; }

 private:
  /// Applies every record the feed has stamped <= t (waiting for a lagging recording).
  void apply_through(TimeUs t, TimeUs previous_t);
  /// The feed ended and t is past its last record: the run has no tick at t.
  bool finished(TimeUs t) const {
    return ended_ && (!run_.any_record || t > run_.latest_record_us);
  }

  InputSource& table_;
  std::optional<SourceFeed> own_feed_;  ///< the first constructor's
  RecordFeed* feed_;
  std::optional<TickGrid> grid_;  ///< unset: from the first record
  double tick_rate_hz_;
  TickRun run_;
  bool ended_ = false;
  InputRecord record_;
};

}  // namespace vmass::runtime
