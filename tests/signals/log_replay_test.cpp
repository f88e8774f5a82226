// replay_candump: ticks in log time from the first frame; a frame at or before a tick is seen
// by it; corrupt lines are skipped and counted; an empty log gives no tick.
#include <gtest/gtest.h>

#include <sstream>
#include <vector>

#include "test_dbc.hpp"
#include "vmass/signals/log_replay.hpp"

namespace vmass::signals {
namespace {

SignalTable speed_table() {
  SignalMapping m;
  const auto decoder = test::test_decoder();
  EXPECT_EQ(parse_signal_mapping(YAML::Load("speed: {message: Speeds, signal: SpeedKmh}"), "t",
                                 *decoder, "t", &m),
            "");
  return SignalTable(decoder, m);
}

// Speeds (0x100) carrying `kmh` km/h: 16-bit Intel, 0.01 km/h.
std::string line(const char* time, int kmh) {
  const int raw = kmh * 100;
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%s) can0 100#%02X%02X000000000000\n", time, raw & 0xFF,
                (raw >> 8) & 0xFF);
  return buf;
}

TEST(LogReplay, TicksFromTheFirstFrameSeeFramesAtOrBeforeThem) {
  SignalTable table = speed_table();
  std::stringstream log;
  log << line("1700000000.500000", 36) << line("1700000000.515000", 72) << "garbage line\n"
      << line("1700000000.530000", 108) << line("1700000000.534000", 144);
  can::CandumpReader reader(log, "t.log");
  std::vector<Sample> ticks;
  const LogReplayStats st =
      replay_candump(reader, table, 100.0, [&](const Sample& s) { ticks.push_back(s); });
  const TimeUs t0 = 1700000000500000;
  EXPECT_EQ(st.first_frame_us, t0);
  EXPECT_EQ(st.last_frame_us, t0 + 34000);
  ASSERT_EQ(st.ticks, 4);  // 0, 10, 20, 30 ms; 40 ms is after the last frame
  ASSERT_EQ(ticks.size(), 4u);
  const double want_mps[] = {10.0, 10.0, 20.0, 30.0};  // the 30 ms frame is seen at 30 ms
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(ticks[k].time_us, t0 + static_cast<TimeUs>(k) * 10000);
    ASSERT_TRUE(ticks[k].has(Input::kSpeed)) << k;
    EXPECT_NEAR(ticks[k].speed_mps, want_mps[k], 1e-12) << k;
  }
  EXPECT_EQ(reader.stats().corrupt, 1u);
  EXPECT_EQ(table.counters().decoded, 4u);
}

TEST(LogReplay, NonIntegerPeriodsDoNotDrift) {
  SignalTable table = speed_table();
  std::stringstream log;
  log << line("0000000000.000000", 36) << line("0000000003.000000", 36);
  can::CandumpReader reader(log, "t.log");
  std::vector<TimeUs> times;
  replay_candump(reader, table, 30.0, [&](const Sample& s) { times.push_back(s.time_us); });
  ASSERT_EQ(times.size(), 91u);  // 0 .. 3 s at 30 Hz
  EXPECT_EQ(times[1], 33333);
  EXPECT_EQ(times[2], 66667);
  EXPECT_EQ(times[90], 3000000);
}

TEST(LogReplay, EmptyOrCorruptOnlyLogGivesNoTick) {
  SignalTable table = speed_table();
  std::stringstream log("# a comment\nnot a frame\n");
  can::CandumpReader reader(log, "t.log");
  int n = 0;
  const LogReplayStats st = replay_candump(reader, table, 100.0, [&](const Sample&) { ++n; });
  EXPECT_FALSE(st.any_frame);
  EXPECT_EQ(st.ticks, 0);
  EXPECT_EQ(n, 0);
  EXPECT_EQ(reader.stats().corrupt, 1u);
}

}  // namespace
}  // namespace vmass::signals
