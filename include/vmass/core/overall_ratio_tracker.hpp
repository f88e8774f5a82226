// OverallRatioTracker: the driveline's overall ratio from the engine speed, for a car whose bus
// carries engine torque and engine speed but no gear number, and whose config has no ratios
// (vehicle.derive_overall_ratio).
//
//   i        = w_engine r / v              engine turns per wheel turn, r the rolling radius
//   C_wheel  = T_engine i eta              (T_engine i / eta while the wheels drag the engine)
//   m_rot(i) = m_wheels + eta J_engine i^2 / r^2     the engine's inertia seen at the wheels
// While the converter is locked or the clutch closed, i is a constant of the engaged gear: a
// plateau. A slipping converter or clutch makes it drift (the stall curve, a clutch closing) or
// sit off the gear's plateau (a converter at its coupling point turns the engine 1 / SR_c
// faster); a shift moves it from one plateau to another.
//   - locked: over the last window_s the ratio stayed within steady_fraction of its mean;
//   - plateaus: a locked tick joins the plateau within match_fraction of its window's mean, or
//     opens a new one; the plateau's id (1, 2, ... in order of discovery) stands in for the gear
//     number, so that a differencing window never spans a shift;
//   - confirmed: a plateau seen locked at confirm_speed_mps or faster, above any converter's
//     lock-up speed: its ratio is a gear's and not a converter's coupling slip. Gear 1 of an
//     automatic never locks and is never confirmed; nor is a gear only driven below that speed.
//     Without a converter (vehicle.torque_converter false) every locked plateau is a gear's.
// The wheel torque uses the plateau's ratio (the mean of every locked tick it has seen), not the
// tick's own: the speed signal's noise would enter the force.
//
// Pure; allocates nothing; not thread-safe (one owner).
#pragma once

#include <array>
#include <string>

#include "vmass/core/vehicle_params.hpp"

namespace vmass {

struct RatioTrackerParams {
  double window_s = 0.3;            ///< the ratio must be steady this long to count as locked
  double steady_fraction = 0.02;    ///< max - min of the window, relative to its mean
  double match_fraction = 0.04;     ///< a window joins a plateau this close (gear steps: >= 10 %)
  double confirm_speed_mps = 12.0;  ///< above every converter's lock-up speed (5-12 m/s)
  double min_speed_mps = 1.0;       ///< below, w r / v is noise over nothing
  double max_ratio = 150.0;         ///< beyond any driveline: a clutch open at low speed

  std::string validate() const;
};

/// What the tracker says of one tick.
struct RatioReading {
  bool locked = false;     ///< the ratio is steady (converter locked or clutch closed)
  bool confirmed = false;  ///< ... on a plateau seen locked above confirm_speed_mps
  int plateau = 0;         ///< 1-based id of the plateau while locked, 0 otherwise
  double ratio = 0.0;      ///< the plateau's ratio while locked, else the tick's own (0: none)
};

class OverallRatioTracker {
 public:
  static constexpr int kMaxPlateaus = 32;  ///< more than any gearbox, with slip plateaus
  static constexpr int kMaxWindowTicks = 256;

  OverallRatioTracker(const VehicleParams& vehicle, const RatioTrackerParams& params,
                      double tick_rate_hz);

  /// One tick. A non-finite or non-positive engine speed, a speed below min_speed_mps or a
  /// ratio above max_ratio breaks the window (unlocked until it is full and steady again).
  RatioReading step(double engine_speed_radps, double speed_mps);
  /// Start the window again (a hole in the data); the plateaus are kept: they are the car's.
  void restart();

  /// C_wheel from the engine torque: at the locked plateau's ratio, else at the last locked
  /// plateau's (the gear most likely still engaged; such ticks are not clean), 0 before any.
  double wheel_torque_nm(double engine_torque_nm) const;
  /// m_rot at the ratio of plateau `id` (rotating_mass_kg alone for 0 or an unknown id), kg.
  double rotating_mass_kg(int id) const;

  const RatioReading& reading() const { return reading_; }
  int plateau_count() const { return plateau_count_; }
  /// The ratio of plateau `id` (1-based); 0 for an unknown id.
  double plateau_ratio(int id) const;
  bool plateau_confirmed(int id) const;

 private:
  struct Plateau {
    double ratio = 0.0;
    double ticks = 0.0;  ///< locked ticks averaged into ratio
    bool confirmed = false;
  };
  /// The plateau within match_fraction of `ratio` (the nearest), or a new one; 0 when full.
  int plateau_for(double ratio);
  void join(int id, double window_mean, double speed_mps);
  bool window_steady(double* mean) const;

  VehicleParams vehicle_;
  RatioTrackerParams params_;
  double confirm_speed_mps_;  ///< params_'s with a torque converter, 0 without
  int window_ticks_;
  std::array<double, kMaxWindowTicks> window_{};
  int window_fill_ = 0;
  int window_next_ = 0;
  std::array<Plateau, kMaxPlateaus> plateaus_{};
  int plateau_count_ = 0;
  int last_locked_ = 0;  ///< the last locked tick's plateau
  RatioReading reading_;
};

}  // namespace vmass
