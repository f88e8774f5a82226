#include "vmass/runtime/tick_driver.hpp"

#include <algorithm>

namespace vmass::runtime {

TickDriver::TickDriver(InputSource& source, double tick_rate_hz)
    : source_(source), tick_rate_hz_(tick_rate_hz) {}

TickRun TickDriver::run(TickClock& clock, const OnTick& on_tick) {
  TickRun run;
  bool pending =
      source_.next_record(0) == InputSource::Read::kRecord;  // the next record, not applied
  if (!pending) return run;
  run.any_record = true;
  run.first_record_us = source_.record_time_us();
  run.latest_record_us = run.first_record_us;
  const TickGrid grid(run.first_record_us, tick_rate_hz_);
  InputRecord record;
  for (std::int64_t k = 0;; ++k) {
    const TimeUs t = grid.time_of(k);
    if (!pending && t > run.latest_record_us) break;  // past the last record: the end
    if (!clock.wait_for_tick(k, t)) {
      run.stopped = true;
      break;
    }
    while (pending && source_.record_time_us() <= t) {
      run.latest_record_us = std::max(run.latest_record_us, source_.record_time_us());
      source_.copy_record(&record);
      source_.apply(record);
      pending = source_.next_record(0) == InputSource::Read::kRecord;
    }
    if (!pending && t > run.latest_record_us) break;
    on_tick(k, t);
    run.ticks = k + 1;
  }
  return run;
}

}  // namespace vmass::runtime
