// TickStats: timing of the estimator's fixed-rate loop: overruns, skipped ticks, period jitter
// percentiles (p50, p99) and maxima, in a fixed-size histogram (no allocation).
//
// For tick k woken at w_k (CLOCK_MONOTONIC) with deadline d_k and nominal period P:
//   period jitter  j_k = | (w_k - w_{k-1}) - P |      (k >= 1)
//   wake latency   l_k = w_k - d_k                   (>= 0 with absolute sleeps)
//   overrun        the tick finished after d_{k+1} (the next tick is already late)
// The jitter histogram is log-linear: 1 us bins below 128 us, then 64 bins per power of two
// (relative resolution 1/64), up to 2^34 us; a percentile is reported as the upper edge of its
// bin (so p50/p99 may read up to 1.6 % high), the maximum exactly.
//
// Thread-safety: not thread-safe (the estimator thread owns it; it publishes summaries).
#pragma once

#include <array>
#include <cstdint>

namespace vmass::service {

/// Fixed-size log-linear histogram of non-negative integer values (microseconds).
class LogHistogram {
 public:
  static constexpr int kLinearBins = 128;  ///< values 0..127 exactly
  static constexpr int kSubBins = 64;      ///< per power of two above
  static constexpr int kMaxExponent = 34;  ///< values up to 2^34 - 1 (larger: last bin)
  static constexpr int kBins = kLinearBins + (kMaxExponent - 7) * kSubBins;

  void add(std::int64_t value);
  void clear();
  std::int64_t count() const { return count_; }
  std::int64_t max() const { return max_; }
  /// Smallest bin upper edge below which at least fraction q (0..1) of the values lie; 0 when
  /// empty.
  std::int64_t percentile(double q) const;

  static int bin_of(std::int64_t value);
  /// Largest value that falls in the bin.
  static std::int64_t bin_upper(int bin);

 private:
  std::array<std::uint32_t, kBins> bins_{};
  std::int64_t count_ = 0;
  std::int64_t max_ = 0;
};

struct TickTimingSummary {
  std::int64_t ticks = 0;
  std::int64_t overruns = 0;
  std::int64_t skipped = 0;
  double jitter_p50_us = 0.0;
  double jitter_p99_us = 0.0;
  double jitter_max_us = 0.0;
  double wake_latency_max_us = 0.0;
  double compute_max_us = 0.0;
};

class TickStats {
 public:
  /// `period_ns` is the nominal wall-clock period of the loop.
  explicit TickStats(std::int64_t period_ns) : period_ns_(period_ns) {}

  /// A tick woke at wake_ns for its deadline deadline_ns (both CLOCK_MONOTONIC).
  void on_wake(std::int64_t deadline_ns, std::int64_t wake_ns);
  /// The tick's work took compute_ns; `overrun` when the next deadline had already passed.
  void on_done(std::int64_t compute_ns, bool overrun);
  /// A tick run without pacing (replay at maximum speed): counted, no timing.
  void on_unpaced_tick() { ++ticks_; }
  /// Ticks given up after a long stall.
  void on_skipped(std::int64_t ticks) { skipped_ += ticks; }

  TickTimingSummary summary() const;
  const LogHistogram& jitter() const { return jitter_us_; }

 private:
  std::int64_t period_ns_;
  LogHistogram jitter_us_;
  std::int64_t ticks_ = 0;
  std::int64_t overruns_ = 0;
  std::int64_t skipped_ = 0;
  std::int64_t last_wake_ns_ = 0;
  bool has_last_wake_ = false;
  std::int64_t wake_latency_max_ns_ = 0;
  std::int64_t compute_max_ns_ = 0;
};

}  // namespace vmass::service
