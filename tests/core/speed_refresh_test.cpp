// Given speed signals as an ESC and as an instrument cluster send them, SpeedRefresh tells them
// apart from how often their value changes while the vehicle speeds up; a cruise, a crawl, a
// hole or a NaN counts nothing.
#include "vmass/core/speed_refresh.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace vmass {
namespace {

constexpr double kKmh = 1.0 / 3.6;

// 100 Hz ticks of a speed v0 + a t, as a bus sends it: refreshed every period_s, in steps of
// quantum_mps (the sample holds the last frame's value between frames).
void drive(SpeedRefresh* refresh, double seconds, double v0_mps, double accel_mps2, double period_s,
           double quantum_mps, TimeUs start_us = 0) {
  double held = std::round(v0_mps / quantum_mps) * quantum_mps;
  double next_frame_s = 0.0;
  for (int i = 0; i * 0.01 < seconds; ++i) {
    const double t = i * 0.01;
    if (t + 1e-9 >= next_frame_s) {
      held = std::round((v0_mps + accel_mps2 * t) / quantum_mps) * quantum_mps;
      next_frame_s += period_s;
    }
    refresh->observe(start_us + from_seconds(t), held);
  }
}

TEST(SpeedRefresh, AnEscSpeedIsFineAndAClusterSpeedIsNot) {
  SpeedRefresh esc;
  drive(&esc, 6.0, 5.0, 0.5, 0.02, 0.01 * kKmh);
  EXPECT_TRUE(esc.decided());
  EXPECT_FALSE(esc.coarse());
  EXPECT_NEAR(esc.mean_interval_s(), 0.02, 0.002);

  // The coarsest ESC step seen on real buses (0.05625 km/h) at a truck's 0.3 m/s^2.
  SpeedRefresh coarse_esc;
  drive(&coarse_esc, 6.0, 5.0, 0.32, 0.02, 0.05625 * kKmh);
  EXPECT_TRUE(coarse_esc.decided());
  EXPECT_FALSE(coarse_esc.coarse());

  // A cluster refreshing every 100 ms in 0.5 km/h steps, even under hard acceleration.
  SpeedRefresh cluster;
  drive(&cluster, 6.0, 5.0, 2.0, 0.1, 0.5 * kKmh);
  EXPECT_TRUE(cluster.coarse());
  EXPECT_GE(cluster.mean_interval_s(), 0.1 - 1e-9);

  SpeedRefresh slow_cluster;
  drive(&slow_cluster, 6.0, 5.0, 0.5, 0.2, 1.0 * kKmh);
  EXPECT_TRUE(slow_cluster.coarse());
}

TEST(SpeedRefresh, ACruiseACrawlOrAHoleCountsNothing) {
  SpeedRefresh cruise;
  drive(&cruise, 60.0, 20.0, 0.0, 0.02, 0.01 * kKmh);
  EXPECT_FALSE(cruise.decided());
  EXPECT_FALSE(cruise.coarse());

  SpeedRefresh crawl;  // below 2 m/s the speed signal says little
  drive(&crawl, 10.0, 0.2, 0.15, 0.02, 0.01 * kKmh);
  EXPECT_FALSE(crawl.decided());

  // Ticks more than 0.1 s apart: no block is ever a second long.
  SpeedRefresh holes;
  for (int i = 0; i < 100; ++i) holes.observe(from_seconds(0.2 * i), 5.0 + 0.1 * i);
  EXPECT_FALSE(holes.decided());

  SpeedRefresh nan;
  for (int i = 0; i < 1000; ++i) {
    nan.observe(from_seconds(0.01 * i),
                i % 50 == 49 ? std::numeric_limits<double>::quiet_NaN() : 5.0 + 0.005 * i);
  }
  EXPECT_FALSE(nan.decided());
}

TEST(SpeedRefresh, TimeGoingBackStartsAFreshBlock) {
  SpeedRefresh refresh;
  drive(&refresh, 2.5, 5.0, 0.5, 0.02, 0.01 * kKmh);
  const double before = refresh.mean_interval_s();
  drive(&refresh, 0.5, 5.0, 0.5, 0.02, 0.01 * kKmh);  // the clock restarted at 0
  EXPECT_DOUBLE_EQ(refresh.mean_interval_s(), before);
  drive(&refresh, 2.0, 5.0, 0.5, 0.02, 0.01 * kKmh, from_seconds(100.0));
  EXPECT_TRUE(refresh.decided());
  EXPECT_FALSE(refresh.coarse());
}

}  // namespace
}  // namespace vmass
