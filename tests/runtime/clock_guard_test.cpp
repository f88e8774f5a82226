// The recording's clock guard (runtime::ClockGuard): records put back in time order within the
// window, too-late ones dropped, one stray stamp dropped (far away, or just ahead: then it
// alone is lost), a gap in the bus kept, a clock that jumps forward or back re-based with a
// bounded gap; every case counted. Then through a candump log: one frame stamped
// 3 years ahead no longer makes the tick driver tick through 1e10 empty ticks.
#include "vmass/runtime/clock_guard.hpp"

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_dbc.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/candump_frame_source.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::runtime {
namespace {

struct Rec {
  TimeUs time_us = 0;
  int tag = 0;
};
using Guard = ClockGuard<Rec>;

/// Pushes (time, tag) pairs, then drains the guard with the input ended.
std::vector<Rec> run(Guard& guard, const std::vector<Rec>& in) {
  std::vector<Rec> out;
  Rec r;
  for (const Rec& x : in) {
    guard.push(x);
    while (guard.pop(&r, false)) out.push_back(r);
  }
  while (guard.pop(&r, true)) out.push_back(r);
  return out;
}

std::vector<int> tags(const std::vector<Rec>& v) {
  std::vector<int> t;
  for (const Rec& r : v) t.push_back(r.tag);
  return t;
}

TEST(ClockGuard, InOrderRecordsPassUnchangedOnceTheWindowHasPassed) {
  Guard guard;
  Rec r;
  guard.push({1'000'000, 1});
  EXPECT_FALSE(guard.pop(&r, false));  // a later record may still overtake it
  guard.push({1'040'000, 2});
  EXPECT_FALSE(guard.pop(&r, false));
  guard.push({1'050'000, 3});  // 1.0 s is now a window behind the newest
  ASSERT_TRUE(guard.pop(&r, false));
  EXPECT_EQ(r.tag, 1);
  EXPECT_EQ(r.time_us, 1'000'000);
  const std::vector<Rec> rest = run(guard, {});
  EXPECT_EQ(tags(rest), (std::vector<int>{2, 3}));
  EXPECT_EQ(guard.counters().reordered, 0);
}

TEST(ClockGuard, RecordsWithinTheWindowAreReorderedLaterOnesDropped) {
  Guard guard;
  // 20 ms late (reordered), 30 ms late (reordered), 60 ms late (dropped); equal times keep order.
  const std::vector<Rec> out = run(guard, {{100'000, 1},
                                           {140'000, 2},
                                           {120'000, 3},
                                           {150'000, 4},
                                           {120'000, 5},
                                           {160'000, 6},
                                           {100'000, 7}});
  EXPECT_EQ(tags(out), (std::vector<int>{1, 3, 5, 2, 4, 6}));
  for (std::size_t i = 1; i < out.size(); ++i) EXPECT_LE(out[i - 1].time_us, out[i].time_us);
  EXPECT_EQ(guard.counters().reordered, 2);
  EXPECT_EQ(guard.counters().late_dropped, 1);
  EXPECT_EQ(guard.counters().time_jumps, 0);
}

TEST(ClockGuard, OneStrayStampFarAwayIsDropped) {
  Guard guard;
  const TimeUs three_years = 100'000'000'000'000;
  const std::vector<Rec> out = run(guard, {{0, 1},
                                           {10'000, 2},
                                           {three_years, 3},  // stray, ahead
                                           {20'000, 4},
                                           {-three_years, 5},  // stray, behind
                                           {30'000, 6}});
  EXPECT_EQ(tags(out), (std::vector<int>{1, 2, 4, 6}));
  EXPECT_EQ(out.back().time_us, 30'000);
  EXPECT_EQ(guard.counters().time_jumps, 2);
}

TEST(ClockGuard, AJumpForwardIsRebasedToABoundedGap) {
  Guard guard;
  const TimeUs hour = 3'600'000'000;
  const std::vector<Rec> out =
      run(guard, {{0, 1}, {10'000, 2}, {hour, 3}, {hour + 10'000, 4}, {hour + 20'000, 5}});
  EXPECT_EQ(tags(out), (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_EQ(out[2].time_us, 10'000 + Guard::kJumpGapUs);
  EXPECT_EQ(out[3].time_us, 10'000 + Guard::kJumpGapUs + 10'000);
  EXPECT_EQ(out[4].time_us, 10'000 + Guard::kJumpGapUs + 20'000);
  EXPECT_EQ(guard.counters().time_jumps, 1);
}

TEST(ClockGuard, AJumpBackIsRebasedNotDroppedAsLate) {
  Guard guard;
  // The clock steps back 10 s: a thousand ticks' worth of frames that must not be lost.
  std::vector<Rec> in = {{20'000'000, 0}, {20'010'000, 1}};
  for (int i = 0; i < 1000; ++i) in.push_back({10'000'000 + i * 10'000, 2 + i});
  const std::vector<Rec> out = run(guard, in);
  ASSERT_EQ(out.size(), in.size());
  EXPECT_EQ(out[2].time_us, 20'010'000 + Guard::kJumpGapUs);
  EXPECT_EQ(out.back().time_us, 20'010'000 + Guard::kJumpGapUs + 999 * 10'000);
  EXPECT_EQ(guard.counters().time_jumps, 1);
  EXPECT_EQ(guard.counters().late_dropped, 0);
}

TEST(ClockGuard, AStrayAtTheEndIsDropped) {
  Guard guard;
  const std::vector<Rec> out = run(guard, {{0, 1}, {10'000, 2}, {900'000'000'000, 3}});
  EXPECT_EQ(tags(out), (std::vector<int>{1, 2}));
  EXPECT_EQ(guard.counters().time_jumps, 1);
}

std::string write_temp(const std::string& text) {
  char name[] = "/tmp/vmass_clock_XXXXXX";
  const int fd = mkstemp(name);
  EXPECT_GE(fd, 0);
  std::ofstream(name) << text;
  return name;
}

// A frame of Speeds (0x100) at `time` carrying 36 km/h.
std::string speed_line(const char* time) {
  return std::string("(") + time + ") can0 100#100E000000000000\n";
}

TEST(ClockGuard, ARecordStampedAheadCostsItselfNotTheRecordsBehindIt) {
  // Two frames of a slow message swapped in the log: the later one (tag 99, 140 ms ahead) comes
  // first. Before: it became the newest, and the records behind it were too late (dropped).
  Guard guard;
  std::vector<Rec> in;
  for (int k = 0; k < 5; ++k) in.push_back({k * 10'000, k});
  in.push_back({180'000, 99});
  for (int k = 5; k < 20; ++k) in.push_back({k * 10'000, k});
  const std::vector<Rec> out = run(guard, in);
  std::vector<int> expected;
  for (int k = 0; k < 20; ++k) expected.push_back(k);
  EXPECT_EQ(tags(out), expected);  // the early one dropped, nothing else
  EXPECT_EQ(guard.counters().time_jumps, 1);
  EXPECT_EQ(guard.counters().late_dropped, 0);
}

TEST(ClockGuard, AGapLongerThanTheWindowLosesNothing) {
  // The bus quiet for 300 ms, and once for 2 s at the very end: every record kept, in order,
  // at its own time.
  Guard guard;
  const std::vector<Rec> out =
      run(guard, {{0, 0}, {10'000, 1}, {310'000, 2}, {315'000, 3}, {312'000, 4}, {2'320'000, 5}});
  EXPECT_EQ(tags(out), (std::vector<int>{0, 1, 2, 4, 3, 5}));
  EXPECT_EQ(out.back().time_us, 2'320'000);
  EXPECT_EQ(guard.counters().time_jumps, 0);
  EXPECT_EQ(guard.counters().late_dropped, 0);
  EXPECT_EQ(guard.counters().reordered, 1);
}

TEST(ClockGuard, ARecordAfterAGapThatTheNextOvertakesIsTakenForAStray) {
  // The price of dropping early strays: the first record after a gap, overtaken by the next,
  // looks like one (lost, counted); the records after it are kept.
  Guard guard;
  const std::vector<Rec> out =
      run(guard, {{0, 0}, {10'000, 1}, {310'000, 2}, {305'000, 3}, {320'000, 4}});
  EXPECT_EQ(tags(out), (std::vector<int>{0, 1, 3, 4}));
  EXPECT_EQ(guard.counters().time_jumps, 1);
  EXPECT_EQ(guard.counters().late_dropped, 0);
}

TEST(ClockGuard, AFrameStampedYearsAheadNoLongerHangsTheTickDriver) {
  std::string log;
  char t[32];
  for (int i = 0; i < 100; ++i) {
    std::snprintf(t, sizeof t, "1700000000.%06d", i * 10000);
    log += speed_line(t);
    if (i == 50) log += speed_line("1800000000.000000");  // three years ahead
  }
  const auto decoder = testing::test_decoder();
  signals::SignalMapping mapping;
  ASSERT_EQ(signals::parse_signal_mapping(YAML::Load("speed: {message: Speeds, signal: SpeedKmh}"),
                                          "t", *decoder, "t", &mapping),
            "");
  std::string error;
  const std::string path = write_temp(log);
  auto frames = CandumpFrameSource::open(path, &error);
  std::remove(path.c_str());
  ASSERT_TRUE(frames) << error;
  CanInputSource source(std::move(frames), decoder, mapping);
  UnpacedClock clock;
  TickDriver driver(source, 100.0);
  const TickRun r = driver.run(clock, [](std::int64_t, TimeUs) {});
  EXPECT_EQ(r.ticks, 100);  // 0 .. 990 ms, not 3 years of ticks
  EXPECT_EQ(source.counters().time_jumps.load(), 1);
  EXPECT_EQ(source.counters().received.load(), 101);
}

}  // namespace
}  // namespace vmass::runtime
