// The one tick loop (runtime::TickDriver on runtime::TickGrid): ticks in log time from the first
// record; a record at or before a tick is seen by it; the last tick is at or before the latest
// record; an empty recording gives no tick; corrupt log lines are skipped and counted; a
// samples CSV's inputs go stale after their timeout; non-integer periods do not drift; the clock
// can stop a run. Expected tick times and values are worked out by hand.
#include "vmass/runtime/tick_driver.hpp"

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_dbc.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/candump_frame_source.hpp"
#include "vmass/runtime/samples_csv_source.hpp"
#include "vmass/runtime/tick_grid.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::runtime {
namespace {

std::string write_temp(const std::string& text) {
  char name[] = "/tmp/vmass_runtime_XXXXXX";
  const int fd = mkstemp(name);
  EXPECT_GE(fd, 0);
  std::ofstream(name) << text;
  return name;
}

// Speeds (0x100) carrying `kmh` km/h: 16-bit Intel, 0.01 km/h.
std::string line(const char* time, int kmh) {
  const int raw = kmh * 100;
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%s) can0 100#%02X%02X000000000000\n", time, raw & 0xFF,
                (raw >> 8) & 0xFF);
  return buf;
}

struct LogInput {
  std::unique_ptr<CanInputSource> source;
  CandumpFrameSource* log = nullptr;
};

LogInput speed_log(const std::string& text) {
  const auto decoder = testing::test_decoder();
  signals::SignalMapping mapping;
  EXPECT_EQ(signals::parse_signal_mapping(YAML::Load("speed: {message: Speeds, signal: SpeedKmh}"),
                                          "t", *decoder, "t", &mapping),
            "");
  mapping.plausibility.enabled = false;  // tick timing with round speeds, not physics
  std::string error;
  const std::string path = write_temp(text);
  auto frames = CandumpFrameSource::open(path, &error);
  std::remove(path.c_str());  // open: read to the end all the same
  EXPECT_TRUE(frames) << error;
  LogInput in;
  in.log = frames.get();
  in.source = std::make_unique<CanInputSource>(std::move(frames), decoder, mapping);
  return in;
}

struct Tick {
  std::int64_t k;
  TimeUs t;
  Sample sample;
};

std::vector<Tick> play(InputSource& source, double rate_hz, TickRun* run = nullptr) {
  std::vector<Tick> ticks;
  UnpacedClock clock;
  TickDriver driver(source, rate_hz);
  const TickRun r = driver.run(clock, [&](std::int64_t k, TimeUs t) {
    ticks.push_back({k, t, source.sample_at(t)});
  });
  if (run) *run = r;
  return ticks;
}

TEST(TickGrid, RoundsEachTickFromItsIndex) {
  const TickGrid grid(1'000'000, 30.0);
  EXPECT_EQ(grid.time_of(0), 1'000'000);
  EXPECT_EQ(grid.time_of(1), 1'033'333);
  EXPECT_EQ(grid.time_of(2), 1'066'667);
  EXPECT_EQ(grid.time_of(90), 4'000'000);  // no drift after 3 s
}

TEST(TickDriver, TicksFromTheFirstRecordSeeRecordsAtOrBeforeThem) {
  LogInput in =
      speed_log(line("1700000000.500000", 36) + line("1700000000.515000", 72) + "garbage line\n" +
                line("1700000000.530000", 108) + line("1700000000.534000", 144));
  TickRun run;
  const std::vector<Tick> ticks = play(*in.source, 100.0, &run);
  const TimeUs t0 = 1700000000500000;
  EXPECT_EQ(run.first_record_us, t0);
  EXPECT_EQ(run.latest_record_us, t0 + 34000);
  ASSERT_EQ(run.ticks, 4);  // 0, 10, 20, 30 ms; 40 ms is after the last record
  ASSERT_EQ(ticks.size(), 4u);
  const double want_mps[] = {10.0, 10.0, 20.0, 30.0};  // the 30 ms frame is seen at 30 ms
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(ticks[k].k, static_cast<std::int64_t>(k));
    EXPECT_EQ(ticks[k].t, t0 + static_cast<TimeUs>(k) * 10000);
    ASSERT_TRUE(ticks[k].sample.has(Input::kSpeed)) << k;
    EXPECT_NEAR(ticks[k].sample.speed_mps, want_mps[k], 1e-12) << k;
  }
  EXPECT_EQ(in.log->stats().corrupt, 1u);
  EXPECT_EQ(in.source->table().counters().decoded, 4u);
}

TEST(TickDriver, NonIntegerPeriodsDoNotDrift) {
  LogInput in = speed_log(line("0000000000.000000", 36) + line("0000000003.000000", 36));
  const std::vector<Tick> ticks = play(*in.source, 30.0);
  ASSERT_EQ(ticks.size(), 91u);  // 0 .. 3 s at 30 Hz
  EXPECT_EQ(ticks[1].t, 33333);
  EXPECT_EQ(ticks[2].t, 66667);
  EXPECT_EQ(ticks[90].t, 3000000);
}

TEST(TickDriver, EmptyOrCorruptOnlyLogGivesNoTick) {
  LogInput in = speed_log("# a comment\nnot a frame\n");
  TickRun run;
  EXPECT_TRUE(play(*in.source, 100.0, &run).empty());
  EXPECT_FALSE(run.any_record);
  EXPECT_EQ(run.ticks, 0);
  EXPECT_EQ(in.log->stats().corrupt, 1u);
}

TEST(TickDriver, SamplesHoldUntilTheirTimeoutThenGoStale) {
  // Rows at 0 and 100 ms, inputs stale after 50 ms: ticks 10..50 ms hold the first row, 60..90 ms
  // see it stale, 100 ms sees the second.
  const std::string csv = write_temp(
      "time_s,wheel_torque_nm,brake_pressure_pa,accel_x_mps2,accel_y_mps2,yaw_rate_radps,"
      "speed_mps,steering_wheel_angle_rad,rear_right_deflection_m,gear\n"
      "0.0,,,,,,1.0,,,\n"
      "0.1,,,,,,2.0,,,\n");
  std::string error;
  auto source = SamplesCsvSource::open(csv, 0.05, &error);
  std::remove(csv.c_str());
  ASSERT_TRUE(source) << error;
  const std::vector<Tick> ticks = play(*source, 100.0);
  ASSERT_EQ(ticks.size(), 11u);
  for (std::size_t k = 0; k <= 5; ++k) {
    EXPECT_TRUE(ticks[k].sample.has(Input::kSpeed)) << k;
    EXPECT_EQ(ticks[k].sample.speed_mps, 1.0) << k;
  }
  for (std::size_t k = 6; k <= 9; ++k) EXPECT_FALSE(ticks[k].sample.has(Input::kSpeed)) << k;
  EXPECT_EQ(ticks[10].sample.speed_mps, 2.0);
  EXPECT_FALSE(ticks[0].sample.has(Input::kWheelTorque));  // an empty cell: invalid
}

TEST(TickDriver, TheClockCanStopTheRun) {
  class StopAtThree final : public TickClock {
   public:
    bool wait_for_tick(std::int64_t k, TimeUs) override { return k < 3; }
  };
  LogInput in = speed_log(line("0.000000", 36) + line("1.000000", 36));
  StopAtThree clock;
  TickDriver driver(*in.source, 100.0);
  int calls = 0;
  const TickRun run = driver.run(clock, [&](std::int64_t, TimeUs) { ++calls; });
  EXPECT_TRUE(run.stopped);
  EXPECT_EQ(run.ticks, 3);
  EXPECT_EQ(calls, 3);
}

}  // namespace
}  // namespace vmass::runtime
