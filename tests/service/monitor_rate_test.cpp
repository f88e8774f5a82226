// vmass-monitor's rates come from the last few seconds and fall to 0 when vmassd stops; a
// silence of three status periods (3 s at least) is reported as the daemon gone.
#include <gtest/gtest.h>

#include <string>

#include "monitor_report.hpp"
#include "recent_rate.hpp"

namespace vmass::monitor {
namespace {

TEST(RecentRate, SteadyArrivalsGiveTheirRate) {
  RecentRate r(5.0);
  for (int k = 0; k <= 1000; ++k) r.add(k * 0.01);  // 100 Hz for 10 s
  EXPECT_NEAR(r.rate_hz(10.0), 100.0, 0.5);
  EXPECT_NEAR(r.rate_hz(10.009), 100.0, 0.5);  // just before the next one
  EXPECT_EQ(r.count(), 1001);
  EXPECT_NEAR(r.mean_interval_s(), 0.01, 1e-9);
}

TEST(RecentRate, StatusAtOneHertzReadsOneHertz) {
  RecentRate r(5.0);
  for (int k = 0; k <= 20; ++k) {
    r.add(k);
    EXPECT_NEAR(r.rate_hz(k + 0.5), k == 0 ? 0.0 : 1.0, 1e-9) << k;
  }
}

TEST(RecentRate, FallsWhenArrivalsStopAndIsZeroOnceTheWindowIsEmpty) {
  RecentRate r(5.0);
  for (int k = 0; k <= 6000; ++k) r.add(k * 0.01);  // 100 Hz for 60 s, then nothing
  EXPECT_NEAR(r.rate_hz(60.0), 100.0, 0.5);
  const double two_s_later = r.rate_hz(62.0);
  EXPECT_LT(two_s_later, 75.0);  // 300 messages over the 5 s window at most
  EXPECT_GT(two_s_later, 50.0);
  EXPECT_LT(r.rate_hz(64.0), 25.0);
  EXPECT_EQ(r.rate_hz(70.0), 0.0);  // the case of issue 32: 10 s after a SIGKILL
  EXPECT_NEAR(r.silent_s(70.0), 10.0, 1e-9);
  EXPECT_EQ(r.count(), 6001);  // the totals stay
}

TEST(RecentRate, ARateChangeShowsWithinTheWindow) {
  RecentRate r(5.0);
  double t = 0.0;
  for (int k = 0; k < 2000; ++k, t += 0.01) r.add(t);  // 100 Hz for 20 s
  for (int k = 0; k < 200; ++k, t += 0.05) r.add(t);   // then 20 Hz for 10 s
  EXPECT_NEAR(r.rate_hz(t), 20.0, 0.5);
}

TEST(RecentRate, NothingYet) {
  RecentRate r(5.0);
  EXPECT_EQ(r.rate_hz(3.0), 0.0);
  EXPECT_LT(r.silent_s(3.0), 0.0);
  r.add(1.0);
  EXPECT_EQ(r.rate_hz(3.0), 0.0);  // one message is no rate
  EXPECT_NEAR(r.silent_s(3.0), 2.0, 1e-9);
}

TEST(SilenceLimit, ThreeStatusPeriodsThreeSecondsAtLeast) {
  EXPECT_DOUBLE_EQ(silence_limit_s(1.0, 0.01), 3.0);
  EXPECT_DOUBLE_EQ(silence_limit_s(0.1, 0.01), 3.0);
  EXPECT_DOUBLE_EQ(silence_limit_s(10.0, 0.01), 30.0);
  EXPECT_DOUBLE_EQ(silence_limit_s(1.0, 5.0), 15.0);  // a heavily decimated estimate
  EXPECT_DOUBLE_EQ(rate_window_s(1.0), 5.0);
  EXPECT_DOUBLE_EQ(rate_window_s(10.0), 30.0);
}

TEST(MonitorReport, SaysWhenVmassdFellSilent) {
  vmass::mass_estimate_t e{};
  vmass::status_t s{};
  s.state_name = "running";
  const Silence quiet{12.4, 12.9, 3.0};
  const std::string report = monitor_report("memq://", 0.0, 0.0, &e, &s, quiet);
  EXPECT_NE(report.find("\nSILENT    no estimate for 12 s: is vmassd running? (last status 13 s "
                        "ago)\n"),
            std::string::npos)
      << report;
  EXPECT_EQ(silence_message({2.0, 1.0, 3.0}), "");     // within the limit
  EXPECT_EQ(silence_message({100.0, -1.0, 0.0}), "");  // no limit
  EXPECT_EQ(silence_message({4.0, -1.0, 3.0}), "no estimate for 4 s: is vmassd running?");
  const std::string fresh = monitor_report("memq://", 100.0, 1.0, &e, &s, {0.01, 0.5, 3.0});
  EXPECT_EQ(fresh.find("SILENT"), std::string::npos) << fresh;
}

}  // namespace
}  // namespace vmass::monitor
