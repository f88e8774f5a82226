// AccuracyMetrics: how good one estimator was on one drive, against the simulator's truth. The
// accuracy suite computes these for every (vehicle, scenario, seed, knowledge, estimator) and
// docs/accuracy.md aggregates them over the population.
//
// Times are measured from the drive's start (Truth::drive_start_us: the first tick at which the
// true speed exceeds 0.5 m/s). Errors are relative to the true mass AT THAT TIME (a load change
// moves the target; tick_comparison.hpp).
//   final_error_pct        (estimate - truth) / truth at the last tick, %
//   error_at_pct[i]        the same at drive start + kCheckpointsS[i] (20 s, 60 s)
//   time_within_since_drive_start_s[j]   the time from the DRIVE'S START after which the
//                          estimate stays within kTolerancesPct[j] (5, 2, 1 %) to the end (0
//                          when within from before the start); NaN when not within at the end
//   rms_last_half_pct      RMS of the relative error over the last half of the ticks
//   covered_at_checkpoint[i], covered_at_end   whether the 95 % interval contains the truth
//                          then (-1: no interval or no estimate)
//   halfwidth_end_pct      the interval's half-width at the end, % of the truth
//   converged_outside_fraction   among the ticks after the first `converged` status, the share
//                          with the truth outside the interval (NaN: never converged)
// A tick without an estimate counts as outside every tolerance. vmass-replay scores otherwise
// (replay_summary.hpp: times from the first tick, coverage of the dynamic ticks).
//
// Not thread-safe; allocates nothing per add().
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "vmass/core/time.hpp"
#include "vmass/scoring/truth.hpp"
#include "vmass/scoring/within_tracker.hpp"

namespace vmass::scoring {

constexpr std::array<double, 2> kCheckpointsS = {20.0, 60.0};
/// The suite's tolerances, in percent of the truth.
constexpr Tolerances kTolerancesPct = {5.0, 2.0, 1.0};

struct EstimatePoint {
  TimeUs time_us = 0;
  bool has_mass = false;
  double mass_kg = 0.0;
  bool has_interval = false;
  double ci_low_kg = 0.0;
  double ci_high_kg = 0.0;
  bool converged = false;
};

struct AccuracyResult {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  long ticks = 0;
  bool has_estimate = false;  ///< an estimate at the last tick
  double final_mass_kg = kNaN;
  double true_final_mass_kg = kNaN;
  double final_error_pct = kNaN;
  std::array<double, kCheckpointsS.size()> error_at_pct{kNaN, kNaN};
  std::array<double, kToleranceCount> time_within_since_drive_start_s{kNaN, kNaN, kNaN};
  double rms_last_half_pct = kNaN;
  std::array<int, kCheckpointsS.size()> covered_at_checkpoint{-1, -1};
  int covered_at_end = -1;
  double halfwidth_end_pct = kNaN;
  double converged_outside_fraction = kNaN;
};

class AccuracyMetrics {
 public:
  explicit AccuracyMetrics(const Truth& truth);

  /// One tick's estimate, in increasing time.
  void add(const EstimatePoint& p);
  AccuracyResult result() const;

 private:
  void check_checkpoints(const EstimatePoint& p, double err, bool covers);
  void end_scores(AccuracyResult* r) const;

  const Truth& truth_;
  TimeUs start_us_;
  std::vector<double> errors_pct_;  ///< per tick (NaN without an estimate), for the RMS
  AccuracyResult r_;
  WithinTracker within_{kTolerancesPct};
  TimeUs last_time_us_ = 0;
  EstimatePoint last_;
  bool seen_converged_ = false;
  long after_converged_ = 0;
  long outside_after_converged_ = 0;
};

}  // namespace vmass::scoring
