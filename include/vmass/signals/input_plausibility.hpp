// InputPlausibility: the estimator inputs the bus reported, checked against physics before the
// estimator sees them (PlausibilityParams for the limits). At each tick, for each input the
// table gave as valid:
//
//   limits          min <= value <= max                                  (every tick)
//   rate of change  |value - previous| / (t_frame - t_previous_frame) <= max_rate_per_s,
//                   between consecutive updates (frame times; at least 5 ms apart); a value
//                   that breaks it is refused until an update that keeps it (a bit flip costs
//                   the flipped frame and the one after)
//   stuck           the value stays within stuck_band of where it stood for stuck_s while
//                   updates come (a dead sensor repeats its value, or its noise around it) and
//                   its witness (valid and not refused all along) moved over that time, at
//                   least 1.5 s before (time to follow):
//                       steering_wheel_angle   the curvature yaw_rate / speed spans >= 0.01
//                                              1/m (24 deg at the wheel of a car), speed >= 3 m/s
//                       yaw_rate               steering angle spans >= 0.35 rad, speed >= 5 m/s
//                       accel_y                yaw_rate * speed spans >= 1.5 m/s^2
//                       accel_x                speed spans >= 3 m/s (off by default: a steady
//                                              acceleration does that; speed_vs_accel_x sees
//                                              a frozen accel_x)
//                   (no witness: stuck when it stays for stuck_s at all); a witness counts
//                   only while it passes its own checks, and was not refused at the last tick
//   speed vs accel_x  over the last window W, with both valid (and not refused by the checks
//                     above) all along:
//                       e = (v(t) - v(t - W)) - integral of accel_x over W   (trapezoids)
//                       d = e - e_slow   (e_slow: e low-passed with smoothing_s, frozen while
//                                         the check fails: the grade and the sensor's bias)
//                       |d| <= tolerance_mps + tolerance_fraction * |integral|   or both fail
//                     and their scale: the changes of delta v and of the integral (each less
//                     its slow mean) fitted as delta v = k * integral over scale_time_s
//                     (exponential forgetting); once excited enough (mean square of the
//                     integral's changes >= 0.25 (m/s)^2), |k - 1| <= scale_tolerance or both
//                     fail: a unit declared wrong (mph read as km/h: k = 0.62, g as m/s^2)
//   yaw rate vs accel_y  in a steady turn over W (speed >= min_speed_mps, |mean accel_y| >=
//                       min_accel_y_mps2, accel_y and yaw rate spreading less than their steady
//                       bounds): |mean r - mean a_y / mean v| <= tolerance_radps +
//                       tolerance_fraction * |mean r|   or both fail
//                       (a kinematic identity in steady cornering: it holds with understeer;
//                       a sign convention flipped in the mapping breaks it)
//
// A failing input is invalid in the Sample, with its verdict (input_verdict.hpp), and counted:
// implausible() is the number of its updates refused. The two cross-checks keep their window's
// sums and extremes as ticks come (O(1) a tick); ticks come in time order (one whose time goes
// back starts the windows anew). Allocates only at construction.
// Not thread-safe: the estimator thread owns it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "vmass/core/sample.hpp"
#include "vmass/signals/input_verdict.hpp"
#include "vmass/signals/plausibility_params.hpp"
#include "vmass/signals/sliding_stats.hpp"

namespace vmass::signals {

class InputPlausibility {
 public:
  explicit InputPlausibility(const PlausibilityParams& params);

  /// Checks the tick's sample in place: a failing input loses its valid bit and gets its
  /// verdict. update_time_us[i]: the time of input i's latest frame (from the table).
  void check(Sample* sample, const TimeUs (&update_time_us)[kInputCount]);

  const InputVerdict& verdict(Input input) const {
    return verdicts_[static_cast<std::size_t>(input)];
  }
  std::int64_t implausible(Input input) const {
    return implausible_[static_cast<std::size_t>(input)];
  }
  /// Forgets the history (windows, references), keeps the counts.
  void reset();

 private:
  struct Track {  ///< per input
    bool has_update = false;
    double last_value = 0.0;
    TimeUs last_update_us = kNeverUs;
    bool rate_fault = false;  ///< the held value broke the rate limit
    InputVerdict rate_verdict;
    // stuck
    bool has_frozen = false;
    double frozen_value = 0.0;
    TimeUs frozen_since_us = 0;
    double witness_min = 0.0, witness_max = 0.0, speed_min = 0.0;
    TimeUs witness_moved_us = kNeverUs;   ///< when the witness first spanned enough
    TimeUs counted_update_us = kNeverUs;  ///< the update last counted as implausible
  };
  struct Row {  ///< one tick of the cross-check window
    TimeUs t = 0;
    double speed = 0.0, accel_x = 0.0, accel_y = 0.0, yaw_rate = 0.0;
    double accel_x_area = 0.0;  ///< accel_x's trapezoid since the row before (both longitudinal)
    bool longitudinal = false;  ///< speed and accel_x valid
    bool lateral = false;       ///< speed, accel_y and yaw_rate valid
  };
  /// Cross-check window: up to this many ticks. A power of two, so that the ring's index is a
  /// mask.
  static constexpr std::size_t kWindowRows = 4096;
  static_assert((kWindowRows & (kWindowRows - 1)) == 0, "kWindowRows must be a power of two");
  /// The rows speed_vs_accel() looks at: [first, newest_] of the run of longitudinal rows that
  /// ends at the newest one, `first` the newest row at least window_s old once there is one
  /// (else the run's oldest). Kept as rows come, so that a tick costs O(1), not O(window); its
  /// sums start from 0 with each run and do not drift (RunningSum).
  struct SpeedWindow {
    TimeUs window_us = 0;
    bool open = false;  ///< the newest row is longitudinal
    std::int64_t first = 0;
    RunningSum area;  ///< the integral of accel_x over the window: of accel_x_area after first
  };
  /// The rows yaw_vs_accel() looks at: [first, newest_] of the run of lateral rows that ends at
  /// the newest one, `first` its oldest row at most window_s old.
  struct YawWindow {
    TimeUs window_us = 0;
    double min_speed = 0.0;
    bool open = false;  ///< the newest row is lateral
    std::int64_t first = 0;
    RunningSum yaw_rate_sum, accel_y_sum, speed_sum;
    std::int64_t slow_rows = 0;  ///< rows below min_speed
    SlidingSpread yaw_rate_spread{kWindowRows}, accel_y_spread{kWindowRows};
  };

  /// Limits and rate of input i (valid in raw).
  InputVerdict check_limits_and_rate(int i, const Sample& raw, TimeUs update_us);
  InputVerdict check_rate(int i, double value, TimeUs update_us);
  /// Stuck: input i's value from raw, its witness from `witnesses` (the inputs that passed).
  InputVerdict check_stuck(int i, const Sample& raw, const Sample& witnesses, TimeUs update_us);
  void push_row(const Sample& s);
  const Row& row_at(std::int64_t seq) const {
    return rows_[static_cast<std::size_t>(seq) & (kWindowRows - 1)];
  }
  /// The i-th newest row (0: the newest); i < count_.
  const Row& row(std::size_t i) const { return row_at(newest_ - static_cast<std::int64_t>(i)); }
  void forget_row(std::int64_t seq);
  void extend_speed_window(bool restart);
  void extend_yaw_window(bool restart);
  void drop_oldest_yaw_row();
  void recompute_speed_sums();
  void recompute_yaw_sums();
  InputVerdict speed_vs_accel();
  void update_scale(double delta_v, double integral, double dt_s);
  InputVerdict scale_verdict() const;
  InputVerdict yaw_vs_accel();
  void flag(Sample* s, int i, const InputVerdict& v, TimeUs update_us);

  PlausibilityParams params_;
  std::array<Track, kInputCount> tracks_{};
  std::array<InputVerdict, kInputCount> verdicts_{};
  std::array<std::int64_t, kInputCount> implausible_{};
  std::vector<Row> rows_;     ///< ring: the last count_ rows, by sequence number
  std::int64_t newest_ = -1;  ///< the newest row's sequence number (rows since reset - 1)
  std::size_t count_ = 0;
  SpeedWindow speed_window_;
  YawWindow yaw_window_;
  /// delta_v = k * integral(accel_x), fitted on their high-passed values (see the header).
  struct ScaleFit {
    double mean_dv = 0.0, mean_int = 0.0;  ///< slow means removed
    double sxy = 0.0, sxx = 0.0, weight = 0.0;
    bool ready = false;
  };
  ScaleFit scale_;
  InputMask refused_last_tick_ = 0;
  double slow_residual_ = 0.0;
  bool has_slow_residual_ = false;
};

}  // namespace vmass::signals
