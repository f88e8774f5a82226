// ReceiveSchedule: when vmassd's receive thread drains a live CAN socket
// (`daemon.receive_period_ms`). Tick k's time T_k falls at mono0 + k P on CLOCK_MONOTONIC and the
// tick wakes P / 2 later, to apply the records stamped <= T_k. The drains fall on the grid
//
//     mono0 + P / 20 + j D,   D = P / n, n = ceil(P / configured period)
//
// so that one drain follows each T_k by P / 20 (0.5 ms at 100 Hz): every frame stamped <= T_k
// is in the ring by then, with 0.45 P to spare before the tick reads it. The frames wait in the
// socket with their kernel stamps, so the ticks see what they would have seen had each frame
// been read at its arrival; the thread wakes once per D instead of at every burst of frames.
// Pure arithmetic on nanoseconds; no clock is read here.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vmass::service {

class ReceiveSchedule {
 public:
  /// The drain period for a configured one (ms; <= 0: read at every frame's arrival, returns
  /// 0): the largest divisor P / n of the tick period P not longer than the configured period.
  static std::int64_t drain_period_ns(double configured_ms, std::int64_t tick_period_ns) {
    if (!(configured_ms > 0.0) || tick_period_ns <= 0) return 0;
    const double per_tick = std::ceil(static_cast<double>(tick_period_ns) / (configured_ms * 1e6));
    return tick_period_ns / static_cast<std::int64_t>(std::max(1.0, per_tick));
  }

  /// tick_period_ns P and drain_period_ns D > 0, D dividing P; mono0_ns: T_0 on CLOCK_MONOTONIC.
  ReceiveSchedule(std::int64_t mono0_ns, std::int64_t tick_period_ns, std::int64_t drain_period_ns)
      : origin_ns_(mono0_ns + tick_period_ns / 20), period_ns_(drain_period_ns) {}

  /// The first drain.
  std::int64_t first_ns() const { return origin_ns_; }

  /// The drain after `previous_ns` (a drain time); after a stall past it (now_ns later), the
  /// first one still ahead of now_ns, on the same grid.
  std::int64_t next_ns(std::int64_t previous_ns, std::int64_t now_ns) const {
    std::int64_t next = previous_ns + period_ns_;
    if (next <= now_ns) next += ((now_ns - next) / period_ns_ + 1) * period_ns_;
    return next;
  }

 private:
  std::int64_t origin_ns_;
  std::int64_t period_ns_;
};

}  // namespace vmass::service
