// The one tick loop (runtime::TickDriver on runtime::TickGrid): ticks in log time from the first
// record; a record at or before a tick is seen by it; the last tick is at or before the latest
// record; an empty recording gives no tick; corrupt log lines are skipped and counted; a
// samples CSV's inputs go stale after their timeout; non-integer periods do not drift; the clock
// can stop a run. Expected tick times and values are worked out by hand.
#include "vmass/runtime/tick_driver.hpp"

#include <atomic>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "test_dbc.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/candump_frame_source.hpp"
#include "vmass/runtime/record_ring.hpp"
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

// The daemon's feed: a reader thread pushes a recording into a small ring (it must wait for room
// again and again), the ticking thread runs the same driver on it: the same ticks, the same
// values as the driver reading the recording itself. The ticking thread's clock does not wait,
// so every tick has to wait for the lagging reader.
TEST(TickDriver, ARingFedByAnotherThreadTicksAsTheRecordingReadInPlace) {
  std::string text;
  for (int i = 0; i < 300; ++i) {
    char time[32];
    std::snprintf(time, sizeof time, "%.6f", 100.0 + i * 0.0137);
    text += line(time, i % 97);
  }
  LogInput offline = speed_log(text);
  const std::vector<Tick> expected = play(*offline.source, 100.0);
  ASSERT_GT(expected.size(), 300u);

  LogInput reader = speed_log(text);
  RecordRing ring(4);
  std::atomic<bool> stop{false};
  ASSERT_EQ(reader.source->next_record(0), InputSource::Read::kRecord);
  const TimeUs t0 = reader.source->record_time_us();
  std::thread push([&] {
    InputRecord record;
    do {
      reader.source->copy_record(&record);
      while (!ring.records.push(record)) std::this_thread::yield();
      if (reader.source->next_record(0) != InputSource::Read::kRecord) break;
      ring.pushed_through_us.store(reader.source->record_time_us() - 1);
    } while (true);
    ring.ended.store(true);
  });
  RingFeed feed(ring, /*recording=*/true, stop);
  UnpacedClock clock;
  TickDriver driver(*reader.source, feed, TickGrid(t0, 100.0));
  std::vector<Tick> ticks;
  const TickRun run = driver.run(clock, [&](std::int64_t k, TimeUs t) {
    ticks.push_back({k, t, reader.source->sample_at(t)});
  });
  push.join();
  ASSERT_EQ(ticks.size(), expected.size());
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    EXPECT_EQ(ticks[i].t, expected[i].t);
    EXPECT_EQ(ticks[i].sample.value(Input::kSpeed), expected[i].sample.value(Input::kSpeed)) << i;
  }
  EXPECT_EQ(run.late_records, 0);
  EXPECT_FALSE(run.stopped);
}

// The reader may push a record and move past the tick between the feed finding the ring empty
// and its look at how far the reader has pushed: the feed looks once more before the tick goes
// on, so the record is that tick's, not a late one (vmassd --replay --speed 1000 once counted
// 1 late record of 112006, its estimates still bit-identical).
TEST(TickDriver, ARecordPushedAsTheReaderMovesOnIsStillTheTicks) {
  RecordRing ring(4);
  std::atomic<bool> stop{false};
  RingFeed feed(ring, /*recording=*/true, stop);
  TimeUs time = 0;
  ASSERT_EQ(feed.peek(&time), RecordFeed::Next::kNotYet);  // empty: tick 10 ms waits
  InputRecord record;
  record.time_us = 9'000;
  ASSERT_TRUE(ring.records.push(record));  // meanwhile the reader pushes a record ...
  ring.pushed_through_us.store(20'000);    // ... and moves on past the tick
  EXPECT_TRUE(feed.wait_for_more(10'000));
  ASSERT_EQ(feed.peek(&time), RecordFeed::Next::kRecord);
  EXPECT_EQ(time, 9'000);
  feed.take(&record);
  EXPECT_EQ(feed.peek(&time), RecordFeed::Next::kNotYet);
  EXPECT_FALSE(feed.wait_for_more(10'000));  // everything stamped <= 10 ms was taken
  EXPECT_TRUE(feed.wait_for_more(20'000));   // the next tick looks once more too
  EXPECT_FALSE(feed.wait_for_more(20'000));
}

// A live feed: a tick takes what has arrived and never waits; a record stamped at or before the
// previous tick arrived too late for it, is applied at the next tick and counted.
TEST(TickDriver, ALiveFeedTakesWhatCameAndCountsTheLate) {
  class TwoTicks final : public TickClock {
   public:
    explicit TwoTicks(RecordRing& ring) : ring_(ring) {}
    bool wait_for_tick(std::int64_t k, TimeUs) override {
      if (k == 1) {
        InputRecord late;
        late.time_us = 5'000;  // stamped before tick 0 (10 ms), read only now
        ring_.records.push(late);
      }
      return k < 2;
    }

   private:
    RecordRing& ring_;
  };
  LogInput in = speed_log(line("0.000000", 36));
  RecordRing ring(8);
  std::atomic<bool> stop{false};
  RingFeed feed(ring, /*recording=*/false, stop);
  TwoTicks clock(ring);
  TickDriver driver(*in.source, feed, TickGrid(10'000, 100.0));
  int calls = 0;
  const TickRun run = driver.run(clock, [&](std::int64_t, TimeUs) { ++calls; });
  EXPECT_EQ(calls, 2);  // tick 0 with an empty ring: no wait
  EXPECT_TRUE(run.stopped);
  EXPECT_EQ(run.late_records, 1);
}

// A clock may give missed ticks up (the daemon on a live bus after a stall): the driver runs
// the tick it names next, on the same grid.
TEST(TickDriver, TheClockCanGiveTicksUp) {
  class SkipAfterTheFirst final : public TickClock {
   public:
    bool wait_for_tick(std::int64_t, TimeUs) override { return true; }
    std::int64_t next_tick(std::int64_t k) override { return k == 0 ? 10 : k + 1; }
  };
  LogInput in = speed_log(line("0.000000", 36) + line("0.120000", 36));
  SkipAfterTheFirst clock;
  TickDriver driver(*in.source, 100.0);
  std::vector<std::int64_t> ks;
  const TickRun run = driver.run(clock, [&](std::int64_t k, TimeUs) { ks.push_back(k); });
  EXPECT_EQ(ks, (std::vector<std::int64_t>{0, 10, 11, 12}));
  EXPECT_EQ(run.ticks, 13);
}

}  // namespace
}  // namespace vmass::runtime
