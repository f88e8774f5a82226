// LaunchIntegrator: each launch from a standstill and each stop to one, the accelerometer's
// change of speed against the speed signal's (TyreWatch). At rest the accelerometer reads the
// grade and its own bias; the integral of a_x less that reading over a launch (or a stop) is the
// true change of speed while the grade holds.
//
// A wheel-speed sensor reads 0 below walking pace, so the standstill's lead_s next to the motion
// (its last before a launch, its first after a stop) belongs to the motion: the reading is the
// rest of the standstill, and the integral holds the lead. A launch counts from rest to end_mps,
// a stop from below end_mps to rest, each within max_launch_s and with its ratio at mid_mps
// agreeing with the whole one within max_ratio_change (a grade that changes under it makes them
// differ; a scale error does not). A stop's reading is known only after it: its integral is kept
// as the sums of a_x and of the time, and the reading taken off at the end.
//
// Pure; allocates nothing; not thread-safe (one owner).
#pragma once

#include <array>

#include "vmass/core/sample.hpp"

namespace vmass {

struct LaunchSpan {
  bool stop = false;      ///< a stop to rest (else a launch from it)
  double wheel_dv = 0.0;  ///< the speed signal's change, m/s
  double accel_dv = 0.0;  ///< the accelerometer's, less its standstill reading, integrated, m/s
};

class LaunchIntegrator {
 public:
  /// true when a launch ended on this tick (its span in *out).
  bool step(const Sample& s, LaunchSpan* out);

 private:
  static constexpr double kStandstillMps = 0.05;
  static constexpr double kMinStandstillS = 1.0;  ///< without the lead
  static constexpr double kLeadS = 0.5;
  static constexpr double kMidSpeedMps = 5.0;
  static constexpr double kEndSpeedMps = 10.0;
  static constexpr double kMaxLaunchS = 15.0;
  static constexpr double kMaxRatioChange = 0.02;
  static constexpr double kMaxTickS = 0.1;        ///< a longer gap is a hole: the launch is dropped
  static constexpr std::size_t kLeadTicks = 128;  ///< the lead's ring (0.5 s at up to 250 Hz)

  struct Tick {
    double dt_s;
    double accel_mps2;
  };

  void forget();
  void start_launch();
  bool finish(double speed_mps, LaunchSpan* out) const;
  /// A stop: its tick above rest (a_x, dt, v), its standstill's (true once it ends).
  void follow_stop(double accel_mps2, double dt, double speed_mps);
  bool stop_at_rest(double accel_mps2, double dt, LaunchSpan* out);

  bool has_last_ = false;
  TimeUs last_us_ = 0;
  // The standstill: every tick's a_x summed; the last ones in a ring (the lead).
  double still_s_ = 0.0;
  double still_sum_ = 0.0;
  long still_n_ = 0;
  std::array<Tick, kLeadTicks> lead_{};
  std::size_t lead_next_ = 0;
  std::size_t lead_count_ = 0;
  // The launch.
  bool launching_ = false;
  double reference_ = 0.0;
  double integral_ = 0.0;
  double launch_s_ = 0.0;
  bool has_mid_ = false;
  double mid_ratio_ = 0.0;
  // The stop: since the speed fell below end_mps, the sums of a_x dt and dt (whole, and to
  // mid_mps), then the standstill after its lead.
  double last_speed_ = 0.0;
  bool stopping_ = false;
  double stop_start_mps_ = 0.0;
  double stop_accel_s_ = 0.0;  ///< sum of a_x dt
  double stop_s_ = 0.0;
  bool stop_has_mid_ = false;
  double stop_mid_mps_ = 0.0;
  double stop_mid_accel_s_ = 0.0;
  double stop_mid_s_ = 0.0;
  double stop_rest_s_ = 0.0;    ///< the standstill after the stop, its lead included
  double stop_rest_sum_ = 0.0;  ///< a_x summed after the lead
  long stop_rest_n_ = 0;
};

}  // namespace vmass
