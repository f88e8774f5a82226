#include "vmass/runtime/tick_driver.hpp"

#include <algorithm>
#include <climits>

namespace vmass::runtime {

TickDriver::TickDriver(InputSource& source, double tick_rate_hz)
    : table_(source),
      own_feed_(std::in_place, source),
      feed_(&*own_feed_),
      tick_rate_hz_(tick_rate_hz) {}

TickDriver::TickDriver(InputSource& table, RecordFeed& feed, const TickGrid& grid)
    : table_(table), feed_(&feed), grid_(grid), tick_rate_hz_(grid.tick_rate_hz()) {}

void TickDriver::apply_through(TimeUs t, TimeUs previous_t) {
  for (;;) {
    TimeUs time = 0;
    const RecordFeed::Next next = feed_->peek(&time);
    if (next == RecordFeed::Next::kEnd) {
      ended_ = true;
      return;
    }
    if (next == RecordFeed::Next::kNotYet) {
      if (feed_->wait_for_more(t)) continue;
      return;
    }
    if (time > t) return;  // the next tick's
    if (time <= previous_t) ++run_.late_records;
    run_.latest_record_us = run_.any_record ? std::max(run_.latest_record_us, time) : time;
    run_.any_record = true;
    feed_->take(&record_);
    table_.apply(record_);
  }
}

TickRun TickDriver::run(TickClock& clock, const OnTick& on_tick) {
  run_ = TickRun{};
  ended_ = false;
  if (!grid_) {
    TimeUs first = 0;
    if (feed_->peek(&first) != RecordFeed::Next::kRecord) return run_;  // an empty recording
    grid_.emplace(first, tick_rate_hz_);
  }
  run_.first_record_us = grid_->t0_us();
  TimeUs previous_t = INT64_MIN;
  for (std::int64_t k = 0;; k = clock.next_tick(k)) {
    const TimeUs t = grid_->time_of(k);
    if (finished(t)) break;
    if (!clock.wait_for_tick(k, t)) {
      run_.stopped = true;
      break;
    }
    apply_through(t, previous_t);
    if (finished(t)) break;
    on_tick(k, t);
    run_.ticks = k + 1;
    previous_t = t;
  }
  return run_;
}

}  // namespace vmass::runtime
