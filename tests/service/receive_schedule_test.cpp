// ReceiveSchedule: the drains of a live socket never come later than the configured period, and
// one falls just after every tick time, well before the tick reads the ring (P / 2 after it).
#include "vmass/service/receive_schedule.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace vmass::service {
namespace {

constexpr std::int64_t kMs = 1'000'000;

TEST(ReceiveSchedule, DrainPeriodDividesTheTickPeriodAndKeepsToTheConfiguredOne) {
  struct Case {
    double configured_ms;
    std::int64_t tick_ns;
    std::int64_t expected_ns;
  };
  for (const Case& c : {Case{10.0, 10 * kMs, 10 * kMs},             // 100 Hz: once a tick
                        Case{10.0, 100 * kMs, 10 * kMs},            // 10 Hz: ten drains a tick
                        Case{3.0, 10 * kMs, 10 * kMs / 4},          // never longer than configured
                        Case{100.0, 10 * kMs, 10 * kMs},            // never longer than a tick
                        Case{10.0, 20 * kMs / 3, 20 * kMs / 3}}) {  // 150 Hz
    const std::int64_t d = ReceiveSchedule::drain_period_ns(c.configured_ms, c.tick_ns);
    EXPECT_EQ(d, c.expected_ns) << c.configured_ms << " ms, tick " << c.tick_ns;
    EXPECT_EQ(c.tick_ns % d, 0);
    EXPECT_LE(d, static_cast<std::int64_t>(c.configured_ms * 1e6));
  }
  EXPECT_EQ(ReceiveSchedule::drain_period_ns(0.0, 10 * kMs), 0);  // read at every arrival
}

TEST(ReceiveSchedule, OneDrainFollowsEveryTickTimeBeforeTheTickReadsTheRing) {
  for (const std::int64_t tick : {10 * kMs, 100 * kMs, 4 * kMs}) {
    const std::int64_t mono0 = 123'456'789;
    const ReceiveSchedule s(mono0, tick, ReceiveSchedule::drain_period_ns(10.0, tick));
    std::int64_t drain = s.first_ns();
    for (std::int64_t k = 0; k < 50; ++k) {
      const std::int64_t tick_time = mono0 + k * tick;
      while (drain <= tick_time) drain = s.next_ns(drain, drain);
      // The first drain after T_k: after T_k, and before the tick wakes at T_k + P / 2.
      EXPECT_GT(drain, tick_time);
      EXPECT_LT(drain, tick_time + tick / 2) << "tick " << k << " of period " << tick;
    }
  }
}

TEST(ReceiveSchedule, AStallResumesOnTheSameGridAheadOfNow) {
  const ReceiveSchedule s(0, 10 * kMs, 10 * kMs);
  const std::int64_t first = s.first_ns();
  EXPECT_EQ(s.next_ns(first, first), first + 10 * kMs);
  const std::int64_t after_stall = s.next_ns(first, first + 1234 * kMs);
  EXPECT_GT(after_stall, first + 1234 * kMs);
  EXPECT_LE(after_stall, first + 1244 * kMs);
  EXPECT_EQ((after_stall - first) % (10 * kMs), 0);
}

}  // namespace
}  // namespace vmass::service
