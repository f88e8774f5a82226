// SpeedRefresh: does the speed signal refresh often enough for its derivative to carry the
// wheels' acceleration over a pair?
//
// A pair's rotating term is m_rot(gear) times the change of the wheels' acceleration over its
// window (LongitudinalExtractor). An ESC's speed refreshes every 10-20 ms in steps of about
// 0.01 km/h, and its derivative after the pair's low-pass carries that change. An instrument
// cluster's displayed speed refreshes every 100-200 ms in steps of 0.5-1 km/h, 0.1-0.3 s late:
// its derivative is a late staircase's, and it misses part of the change. In a truck's first
// gear, whose rotating masses are most of the truck's own, that read the mass 24-44 % high with
// no other effect simulated (tractor-200009, urban and paper_exp1).
//
// What tells the two apart needs no DBC attribute: while the vehicle speeds up or slows down
// (by at least min_change_mps_per_s over a block, above min_speed_mps), a fine signal changes
// its value every few ticks and a displayed one at most once per frame. The signal is coarse
// when the mean interval between its changes over such blocks is above max_mean_interval_s:
// between an ESC's slowest case (steps of 0.056 km/h at 0.3 m/s^2, one change per 52 ms) and
// the fastest cluster frame (100 ms). Two half-second blocks tell it within the first seconds of
// a launch, before the longitudinal block's first pair at 2 m/s: a truck's first gear, whose
// pairs carry the largest rotating term, is then already read right.
//
// Pure; not thread-safe (one owner).
#pragma once

#include "vmass/core/time.hpp"

namespace vmass {

struct SpeedRefreshParams {
  double block_s = 0.5;
  double min_change_mps_per_s = 0.3;  ///< a block counts when the speed changed this much
  double min_speed_mps = 1.0;         ///< ... and stayed above this (wheel sensors' floor)
  long min_blocks = 2;                ///< blocks counted before a verdict
  double max_mean_interval_s = 0.08;  ///< a signal that changes less often is coarse
  double max_tick_gap_s = 0.1;        ///< a longer gap between ticks abandons the block
};

class SpeedRefresh {
 public:
  explicit SpeedRefresh(const SpeedRefreshParams& params = {});

  /// One tick's speed signal as decoded (before any filter), at time_us.
  void observe(TimeUs time_us, double speed_mps);
  /// Enough blocks were counted to tell.
  bool decided() const { return counted_blocks_ >= params_.min_blocks; }
  /// Decided, and the signal changed too seldom: its derivative cannot carry the wheels'
  /// acceleration over a pair. Undecided signals are not coarse.
  bool coarse() const;
  /// Counted seconds per change (infinity before the first change).
  double mean_interval_s() const;

 private:
  void start_block(TimeUs time_us, double speed_mps);
  void close_block(TimeUs time_us, double speed_mps);

  SpeedRefreshParams params_;
  bool in_block_ = false;
  bool block_above_min_speed_ = false;
  TimeUs block_start_us_ = 0;
  double block_start_speed_mps_ = 0.0;
  long block_changes_ = 0;
  TimeUs last_us_ = 0;
  double last_speed_mps_ = 0.0;
  double counted_s_ = 0.0;
  long counted_changes_ = 0;
  long counted_blocks_ = 0;
};

}  // namespace vmass
