// vmass-monitor says why the longitudinal block took no pair lately: from the cumulative verdict
// counts of vmassd's statuses, the stretch since the accepted count last moved and each other
// verdict's ticks over it, once it is 30 s of ticks long; a restarted vmassd starts it again.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "verdict_history.hpp"

namespace vmass::monitor {
namespace {

/// vmassd's status as the monitor gets it: counts of accepted, small_delta_force, settling and
/// speed since the start, at 100 Hz.
struct FakeDaemon {
  std::int64_t ticks = 0;
  std::vector<std::int64_t> counts = {0, 0, 0, 0};
  /// One second of ticks: `accepted` pairs, the rest split between the other verdicts.
  vmass::status_t second(std::int64_t accepted, std::int64_t settling = 0, std::int64_t speed = 0) {
    ticks += 100;
    counts[0] += accepted;
    counts[2] += settling;
    counts[3] += speed;
    counts[1] += 100 - accepted - settling - speed;
    vmass::status_t s{};
    s.ticks = ticks;
    s.tick_rate_hz = 100.0;
    s.num_verdicts = 4;
    s.verdict_name = {"accepted", "small_delta_force", "settling", "speed"};
    s.longitudinal_verdict_ticks = counts;
    s.lateral_verdict_ticks = {0, 0, 0, 0};
    return s;
  }
};

using Ticks = std::vector<std::pair<std::string, std::int64_t>>;

TEST(VerdictHistory, TheStretchSinceTheLastPairWithItsVerdictsMostFirst) {
  VerdictHistory h;
  FakeDaemon d;
  double t = 0.0;
  for (int k = 0; k < 20; ++k, t += 1.0) h.add(t, d.second(3));  // pairs coming
  EXPECT_EQ(h.no_pair().span_s, 0.0);
  for (int k = 0; k < 29; ++k, t += 1.0) h.add(t, d.second(0, k < 2 ? 100 : 0));
  EXPECT_EQ(h.no_pair().span_s, 0.0) << "29 s: not yet";
  h.add(t, d.second(0, 0, 1));
  t += 1.0;
  const NoPairStretch at30 = h.no_pair();
  EXPECT_DOUBLE_EQ(at30.span_s, 30.0);
  EXPECT_EQ(at30.verdict_ticks,
            (Ticks{{"small_delta_force", 2799}, {"settling", 200}, {"speed", 1}}));
  for (int k = 0; k < 150; ++k, t += 1.0) h.add(t, d.second(0));
  const NoPairStretch at180 = h.no_pair();
  EXPECT_DOUBLE_EQ(at180.span_s, 180.0);  // from the last status with a pair, 180 s ago
  EXPECT_EQ(at180.verdict_ticks,
            (Ticks{{"small_delta_force", 17799}, {"settling", 200}, {"speed", 1}}));
  for (int k = 0; k < 60; ++k, t += 1.0) h.add(t, d.second(0));
  EXPECT_DOUBLE_EQ(h.no_pair().span_s, 180.0);  // 3 min kept: no longer than that
  h.add(t, d.second(1));                        // a pair: the stretch is over
  EXPECT_EQ(h.no_pair().span_s, 0.0);
  EXPECT_TRUE(h.no_pair().verdict_ticks.empty());
}

TEST(VerdictHistory, MeasuredInTicksNotInTheMonitorsTime) {
  VerdictHistory h;
  FakeDaemon d;
  // A replay at 20x: a status every 0.05 s of the monitor's clock holds 1 s of ticks.
  for (int k = 0; k < 100; ++k) h.add(k * 0.05, d.second(0));
  EXPECT_DOUBLE_EQ(h.no_pair().span_s, 99.0);
}

TEST(VerdictHistory, ARestartedDaemonStartsAgain) {
  VerdictHistory h;
  FakeDaemon d;
  double t = 0.0;
  for (int k = 0; k < 60; ++k, t += 1.0) h.add(t, d.second(0));
  EXPECT_DOUBLE_EQ(h.no_pair().span_s, 59.0);
  FakeDaemon restarted;
  for (int k = 0; k < 10; ++k, t += 1.0) h.add(t, restarted.second(0));
  EXPECT_EQ(h.no_pair().span_s, 0.0) << "9 s since the restart";
  for (int k = 0; k < 40; ++k, t += 1.0) h.add(t, restarted.second(0));
  EXPECT_DOUBLE_EQ(h.no_pair().span_s, 49.0);
}

TEST(VerdictHistory, StatusesWithoutVerdictsAreIgnored) {
  VerdictHistory h;
  vmass::status_t s{};
  s.ticks = 100;
  s.tick_rate_hz = 100.0;
  for (int k = 0; k < 100; ++k, s.ticks += 100) h.add(k, s);
  EXPECT_EQ(h.no_pair().span_s, 0.0);
  s.num_verdicts = 2;  // arrays shorter than they say: not trusted
  s.verdict_name = {"accepted"};
  s.longitudinal_verdict_ticks = {0};
  for (int k = 0; k < 100; ++k, s.ticks += 100) h.add(100 + k, s);
  EXPECT_EQ(h.no_pair().span_s, 0.0);
}

}  // namespace
}  // namespace vmass::monitor
