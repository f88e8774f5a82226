// The daemon's clocks: CLOCK_MONOTONIC for pacing (absolute sleeps that a stop request
// interrupts within 100 ms), CLOCK_REALTIME for live frames' kernel stamps, and the two read
// together. Private to vmass_service. Thread-safe (plain system calls).
#pragma once

#include <time.h>

#include <atomic>
#include <cstdint>

#include "vmass/core/time.hpp"

namespace vmass::service::daemon {

constexpr std::int64_t kNsPerSecond = 1'000'000'000;
constexpr std::int64_t kPollNs = 100'000'000;  // longest uninterrupted wait: 100 ms

std::int64_t mono_ns();
TimeUs realtime_us();
timespec to_timespec(std::int64_t ns);

/// Absolute sleep on CLOCK_MONOTONIC until deadline_ns, in slices of at most 100 ms so that a
/// stop request is seen. Returns false when stopped first.
bool sleep_until(std::int64_t deadline_ns, const std::atomic<bool>& stop);

/// CLOCK_REALTIME and CLOCK_MONOTONIC read together: the pair of the tightest of up to three
/// realtime-monotonic-realtime brackets (a preemption between two reads would skew it).
struct ClockPair {
  TimeUs realtime_us = 0;
  std::int64_t mono_ns = 0;
};
ClockPair read_clocks();

}  // namespace vmass::service::daemon
