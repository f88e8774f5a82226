// SpeedSignalScale: how fast the engine turns against the speed signal through the gear while
// the driveline is locked, learnt on the drive. The speed signal is not always the wheels':
// an instrument cluster's display speed over-reads by 1-4 % and a few tenths of a m/s (by
// regulation it never reads low), so a locked engine turns 5-11 % "slower" than the display
// speed through the gear says, and the driveline's slip check (max_driveline_slip_fraction)
// would call every tick slipping.
//
//   q = w_engine / (|v| / r i(gear))      1 on a locked driveline with the wheels' speed
// The scale is the running median of q (a step of step_per_tick towards each tick's q) over the
// ticks that can only be locked: in gear, above min_speed_mps (with a converter, above its
// lock-up: confirm_speed_mps), q in [1 - max_overread, 1 + max_underread]. A speed signal
// over-reads (a display) or is off by the tyres' radius (a few %, either way); an engine
// faster than that is a slipping clutch or converter, never the signal's scale. The slip check and
// the converter's map then read the engine against the speed through the gear times the scale.
//
// Pure; allocates nothing; not thread-safe (one owner).
#pragma once

namespace vmass {

struct SpeedSignalScaleParams {
  double step_per_tick = 1e-4;      ///< the median's step: 0.01 a second at 100 Hz
  double max_overread = 0.15;       ///< a display reads at most 10 % + 4 km/h high (UNECE R39)
  double max_underread = 0.03;      ///< the tyres' radius
  double min_speed_mps = 2.0;       ///< clutch gearboxes: below, a launch's clutch slips
  double confirm_speed_mps = 12.0;  ///< converters: above every lock-up speed (5-12 m/s)
};

class SpeedSignalScale {
 public:
  SpeedSignalScale(const SpeedSignalScaleParams& params, bool torque_converter)
      : params_(params),
        min_speed_mps_(torque_converter ? params.confirm_speed_mps : params.min_speed_mps) {}

  /// A tick in a gear held since the previous one: engine speed and the speed through the gear
  /// (rad/s) at the signal's speed (m/s).
  void observe(double engine_radps, double through_gear_radps, double speed_mps);
  /// The median q so far (1 until a tick has been seen).
  double scale() const { return scale_; }

 private:
  SpeedSignalScaleParams params_;
  double min_speed_mps_;
  double scale_ = 1.0;
};

}  // namespace vmass
