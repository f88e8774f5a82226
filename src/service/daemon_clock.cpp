#include "daemon_clock.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>

namespace vmass::service::daemon {

std::int64_t mono_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerSecond + ts.tv_nsec;
}

TimeUs realtime_us() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<TimeUs>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000;
}

timespec to_timespec(std::int64_t ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(ns / kNsPerSecond);
  ts.tv_nsec = static_cast<long>(ns % kNsPerSecond);
  return ts;
}

bool sleep_until(std::int64_t deadline_ns, const std::atomic<bool>& stop) {
  while (!stop.load(std::memory_order_relaxed)) {
    const std::int64_t now = mono_ns();
    if (now >= deadline_ns) return true;
    const std::int64_t until = std::min(deadline_ns, now + kPollNs);
    const timespec ts = to_timespec(until);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
  return false;
}

ClockPair read_clocks() {
  ClockPair best;
  TimeUs best_width = INT64_MAX;
  for (int i = 0; i < 3 && best_width > 20; ++i) {
    const TimeUs rt1 = realtime_us();
    const std::int64_t mono = mono_ns();
    const TimeUs rt2 = realtime_us();
    if (rt2 - rt1 < best_width) {
      best_width = rt2 - rt1;
      best = ClockPair{rt1 + (rt2 - rt1) / 2, mono};
    }
  }
  return best;
}

}  // namespace vmass::service::daemon
