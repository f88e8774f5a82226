// Tick statistics, the seqlock, the SPSC ring, sample_at() and the lcm:/daemon: config sections.
#include <algorithm>
#include <atomic>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "test_drive.hpp"
#include "vmass/config/config.hpp"
#include "vmass/runtime/input_source.hpp"
#include "vmass/runtime/seqlock.hpp"
#include "vmass/runtime/spsc_queue.hpp"
#include "vmass/service/service_config.hpp"
#include "vmass/service/tick_stats.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::service {
namespace {

using runtime::InputTimeouts;
using runtime::InputValues;
using runtime::SeqLock;
using runtime::SpscQueue;

TEST(LogHistogram, BinsCoverEveryValueOnceAndInOrder) {
  // bin_upper(bin_of(v)) >= v, and the previous bin ends below v: bins tile the line.
  for (std::int64_t v :
       {0LL, 1LL, 127LL, 128LL, 129LL, 255LL, 256LL, 1000LL, 4095LL, 4096LL, 123456LL, 9999999LL}) {
    const int b = LogHistogram::bin_of(v);
    EXPECT_GE(LogHistogram::bin_upper(b), v) << v;
    if (b > 0) {
      EXPECT_LT(LogHistogram::bin_upper(b - 1), v) << v;
    }
    // Relative resolution 1/64 above the linear range.
    if (v >= 128) {
      EXPECT_LE(LogHistogram::bin_upper(b) - v, v / 64 + 1) << v;
    }
  }
  for (int b = 1; b < LogHistogram::kBins - 1; ++b) {
    EXPECT_GT(LogHistogram::bin_upper(b), LogHistogram::bin_upper(b - 1));
    EXPECT_EQ(LogHistogram::bin_of(LogHistogram::bin_upper(b)), b);
  }
}

TEST(LogHistogram, PercentilesMatchSortedDataWithinBinResolution) {
  std::mt19937 rng(3);
  std::lognormal_distribution<double> dist(4.0, 1.2);  // ~55 us median, long tail
  std::vector<std::int64_t> values;
  LogHistogram h;
  for (int i = 0; i < 20000; ++i) {
    const auto v = static_cast<std::int64_t>(dist(rng));
    values.push_back(v);
    h.add(v);
  }
  std::sort(values.begin(), values.end());
  for (double q : {0.5, 0.9, 0.99}) {
    const std::int64_t exact =
        values[static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size()))) - 1];
    const std::int64_t got = h.percentile(q);
    EXPECT_GE(got, exact) << q;
    EXPECT_LE(got, exact + exact / 64 + 1) << q;
  }
  EXPECT_EQ(h.max(), values.back());
  EXPECT_EQ(h.count(), 20000);
}

TEST(TickStats, JitterIsTheDeviationOfThePeriod) {
  TickStats stats(10'000'000);  // 10 ms
  // Wake-ups: on time, 300 us late, on time, 2 ms late: periods 10.3, 9.7, 12.0 ms.
  const std::int64_t deadlines[] = {0, 10'000'000, 20'000'000, 30'000'000};
  const std::int64_t wakes[] = {0, 10'300'000, 20'000'000, 32'000'000};
  for (int i = 0; i < 4; ++i) {
    stats.on_wake(deadlines[i], wakes[i]);
    stats.on_done(50'000, i == 3);
  }
  stats.on_skipped(5);
  const TickTimingSummary s = stats.summary();
  EXPECT_EQ(s.ticks, 4);
  EXPECT_EQ(s.overruns, 1);
  EXPECT_EQ(s.skipped, 5);
  // Jitters 300, 300, 2000 us: the median is reported as the upper edge of 300's bin
  // ([300, 303]: 4 us wide between 256 and 511).
  EXPECT_EQ(LogHistogram::bin_upper(LogHistogram::bin_of(300)), 303);
  EXPECT_EQ(s.jitter_p50_us, 303.0);
  EXPECT_EQ(s.jitter_p99_us, 2000.0);
  EXPECT_EQ(s.jitter_max_us, 2000.0);
  EXPECT_EQ(s.wake_latency_max_us, 2000.0);
  EXPECT_EQ(s.compute_max_us, 50.0);
}

TEST(SpscQueue, FifoBoundedAndLossless) {
  SpscQueue<int> q(5);  // rounded to 8
  EXPECT_EQ(q.capacity(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_TRUE(q.push(i));
  EXPECT_FALSE(q.push(99));
  int v = -1;
  for (int i = 0; i < 8; ++i) {
    ASSERT_TRUE(q.pop(&v));
    EXPECT_EQ(v, i);
  }
  EXPECT_FALSE(q.pop(&v));

  // Two threads: every value arrives once, in order.
  SpscQueue<long> ring(64);
  constexpr long kCount = 200000;
  std::thread producer([&] {
    for (long i = 0; i < kCount;) {
      if (ring.push(i)) ++i;
    }
  });
  long expected = 0, got = 0;
  while (expected < kCount) {
    if (ring.pop(&got)) {
      ASSERT_EQ(got, expected);
      ++expected;
    }
  }
  producer.join();
}

struct Wide {
  std::int64_t a[17];
};

TEST(SeqLock, ReadersNeverSeeATornValue) {
  SeqLock<Wide> lock;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    Wide w{};
    for (std::int64_t i = 1; i <= 200000; ++i) {
      for (auto& x : w.a) x = i;
      lock.write(w);
    }
    done = true;
  });
  std::int64_t last = 0;
  long reads = 0;
  while (!done || reads < 10) {
    const Wide w = lock.read();
    for (auto x : w.a) ASSERT_EQ(x, w.a[0]);
    ASSERT_GE(w.a[0], last);  // never goes back
    last = w.a[0];
    ++reads;
  }
  writer.join();
  EXPECT_EQ(lock.read().a[16], 200000);
  EXPECT_EQ(lock.version(), 200000u);
}

TEST(SampleAt, InputsGoStalePerTimeout) {
  InputValues v;
  v.latest.set(Input::kSpeed, 3.0);
  v.latest.set(Input::kAccelX, 0.5);
  v.input_time_us[static_cast<int>(Input::kSpeed)] = 1'000'000;
  v.input_time_us[static_cast<int>(Input::kAccelX)] = 1'040'000;
  InputTimeouts t;
  for (auto& x : t.timeout_us) x = 50'000;
  Sample s = sample_at(v, 1'050'000, t);  // speed 50 ms old: still valid (<=)
  EXPECT_EQ(s.time_us, 1'050'000);
  EXPECT_TRUE(s.has(Input::kSpeed));
  EXPECT_TRUE(s.has(Input::kAccelX));
  EXPECT_FALSE(s.has(Input::kYawRate));  // never received
  s = sample_at(v, 1'050'001, t);
  EXPECT_FALSE(s.has(Input::kSpeed));
  EXPECT_TRUE(s.has(Input::kAccelX));
  EXPECT_EQ(s.speed_mps, 3.0);  // value kept, only flagged
}

// ------------------------------------------------------------------------------ config

ServiceSettingsLoad load(const std::string& extra, std::string* config_error = nullptr) {
  ConfigLoad c = load_config_text(test::test_config_yaml(extra), "vmassd.yaml");
  if (!c.ok()) {
    if (config_error) *config_error = c.error;
    ServiceSettingsLoad out;
    out.error = c.error;
    return out;
  }
  return load_service_settings(*c.config);
}

TEST(ServiceConfig, DefaultsWhenSectionsAreAbsent) {
  const ServiceSettingsLoad r = load("");
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.settings.lcm.url, "udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(r.settings.lcm.estimate_channel, "VMASS_ESTIMATE");
  EXPECT_EQ(r.settings.lcm.status_channel, "VMASS_STATUS");
  EXPECT_FALSE(r.settings.lcm.publish_pairs);
  EXPECT_EQ(r.settings.daemon.can_interface, "can0");
  EXPECT_EQ(r.settings.daemon.realtime.priority, 0);
  EXPECT_TRUE(r.settings.dbc_path.empty());
}

TEST(ServiceConfig, ReadsEveryKey) {
  const ServiceSettingsLoad r = load(
      "lcm:\n  url: memq://\n  estimate_channel: E\n  status_channel: S\n  pairs_channel: P\n"
      "  estimate_decimation: 5\n  status_period_s: 0.5\n  publish_pairs: true\n"
      "daemon:\n  can_interface: vcan0\n  state_file: /tmp/x.state\n  persist_interval_s: 2\n"
      "  input_timeout_s: 0.2\n  publish_queue: 64\n  receive_period_ms: 2.5\n"
      "  realtime:\n    priority: 40\n    cpu_affinity: [1, 3]\n    lock_memory: true\n"
      "can:\n  dbc: car.dbc\n");
  ASSERT_TRUE(r.ok()) << r.error;
  const ServiceSettings& s = r.settings;
  EXPECT_EQ(s.lcm.url, "memq://");
  EXPECT_EQ(s.lcm.estimate_decimation, 5);
  EXPECT_EQ(s.lcm.status_period_s, 0.5);
  EXPECT_TRUE(s.lcm.publish_pairs);
  EXPECT_EQ(s.daemon.can_interface, "vcan0");
  EXPECT_EQ(s.daemon.persist_interval_s, 2.0);
  EXPECT_EQ(s.daemon.publish_queue, 64);
  EXPECT_EQ(s.daemon.receive_period_ms, 2.5);
  EXPECT_EQ(s.daemon.realtime.priority, 40);
  EXPECT_EQ(s.daemon.realtime.cpu_affinity, (std::vector<int>{1, 3}));
  EXPECT_TRUE(s.daemon.realtime.lock_memory);
  EXPECT_EQ(s.dbc_path, "car.dbc");  // in-memory config: no directory to resolve against
}

TEST(ServiceConfig, ErrorsNameFileLineAndKey) {
  // Line numbers: the test config has 17 lines before `extra`.
  ServiceSettingsLoad r = load("lcm:\n  urll: memq://\n");
  EXPECT_EQ(r.error, "vmassd.yaml:19: lcm.urll: unknown key");
  r = load("daemon:\n  realtime:\n    priority: 120\n");
  EXPECT_EQ(r.error, "vmassd.yaml:20: daemon.realtime.priority: must be in [0, 99]");
  r = load("lcm:\n  estimate_decimation: 0\n");
  EXPECT_EQ(r.error, "vmassd.yaml:19: lcm.estimate_decimation: must be >= 1");
  r = load("daemon:\n  realtime:\n    cpu_affinity: [1.5]\n");
  EXPECT_NE(r.error.find("vmassd.yaml:20: daemon.realtime.cpu_affinity"), std::string::npos)
      << r.error;
  r = load("daemon:\n  receive_period_ms: 250\n");
  EXPECT_EQ(r.error,
            "vmassd.yaml:19: daemon.receive_period_ms: must be in [0, 100] (0: read as frames "
            "arrive)");
  r = load("lcm:\n  publish_pairs: maybe\n");
  EXPECT_NE(r.error.find("vmassd.yaml:19: lcm.publish_pairs: expected true or false"),
            std::string::npos)
      << r.error;
}

TEST(ServiceConfig, TheShippedExampleConfigIsValid) {
  const ConfigLoad c = load_config(std::string(VMASS_SOURCE_DIR) + "/config/vmassd.example.yaml");
  ASSERT_TRUE(c.ok()) << c.error;
  const ServiceSettingsLoad r = load_service_settings(*c.config);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.settings.dbc_path, std::string(VMASS_SOURCE_DIR) + "/config/demo_vehicle.dbc");
  // Its can: section maps every estimator input on the demo vehicle's DBC, but for the
  // stand-ins of a bus without wheel torque or brake pressure (this car has both).
  const signals::CanInputsLoad can = signals::load_can_inputs(*c.config);
  ASSERT_TRUE(can.ok()) << can.error;
  const InputMask stand_ins = input_bit(Input::kBrakeSwitch) | input_bit(Input::kEngineTorque) |
                              input_bit(Input::kEngineSpeed);
  for (int i = 0; i < kInputCount; ++i) {
    const auto in = static_cast<Input>(i);
    EXPECT_EQ(can.inputs->mapping.find(in) != nullptr, (input_bit(in) & stand_ins) == 0)
        << input_name(in);
  }
}

}  // namespace
}  // namespace vmass::service
