// LongitudinalExtractor: longitudinal regression pairs (paper eqs. 4-7, Table II), made to hold
// on a car it was not tuned for.
//
//   F   = C_wheel / r_wheel - 0.5 rho C_d A v^2           eqs. (6), (4) with the nominal aero
//   M da_x = dF - m_rot dv'                                  eq. (5); a_x the accelerometer,
//                                                            v' the wheel-speed derivative
// so the pair is  y = dF - m_rot(gear) dv',  phi = [da_x, 1]  and theta[0] is the mass M.
// The accelerometer reads specific force, so the grade cancels exactly in M a_x = F - resistances;
// the rotating parts turn with the wheels, so their inertia multiplies the wheel-speed
// derivative, not a_x. Where the speed signal refreshes too seldom for its derivative to follow
// the wheels within a pair (an instrument cluster's displayed speed, SpeedRefresh), a_x stands
// in for it (rotating_accel_source).
//
// What makes the differenced model hold on real signals:
//   - the same low-pass (estimator.filter_cutoff_hz) on F, a_x and v' before differencing over
//     estimator.differencing_dt_s: the driveline's ringing, the accelerometer's vibration and
//     the bus's quantisation lie above it, and M da = dF still holds between filtered signals;
//   - the driveline's force is run through its gear's torsional mode, as DrivelineMode
//     identifies it from the accelerometer: below its resonance the mode amplifies the hub's
//     torque, which the low-pass keeps (a truck's first gear rings at 1.2-2.5 Hz);
//   - the force is taken at the lag the LagEstimator identifies (the lag at which the pairs fit
//     best), so that it is paired with the acceleration of the same instant; the excited pairs
//     seen before the lag is identified are kept (verdict awaiting_lag) and released, at the
//     identified lag, through pop_released() once it is: no pair enters misaligned;
//   - excitation gates relative to the measured noise: |dF| and M_ref |da| above
//     min_excitation_sigma times the robust scale of the residual dF - M_ref da (measured on
//     every clean tick, M_ref the prior's mass: it does not follow the estimate), with floors;
//   - a pair is taken only when the whole window (and settle_s before it) was clean: no brake
//     (the brake gain is the least known; use_braking allows braking pairs), no engine dragged
//     in overrun (an ECU's drag torque is its least accurate; use_overrun allows it; an
//     electric drive's regeneration is clean), no gear change and a valid gear (with
//     vehicle.derive_overall_ratio: the ratio locked on one confirmed plateau of
//     OverallRatioTracker), a driveline that is locked or, with the converter's map
//     configured, driving through an unlocked converter (ConverterMap: the engine torque times
//     its torque ratio), speed above min_speed_mps, |a_y| small. A wheel torque beside the
//     engine speed, the gear and the ratios is read the same way for the converter's share of
//     it (the gearbox controller's own model of the multiplication is in that torque, with the
//     map's error), and is used through a slip as without them;
//   - an outlier gate that cannot lock in: the mass the pair implies, y / da, must lie in the
//     plausible band [0.5 empty, 1.5 maximum permissible] (2.5 empty without a maximum).
// Without a brake-pressure signal the brake-light switch decides; with neither, the block needs
// use_braking = false and takes no pair while the torque is negative or small (it cannot tell).
//
// Not thread-safe; allocates only in the constructor.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/core/converter_map.hpp"
#include "vmass/core/delay_line.hpp"
#include "vmass/core/differencing_history.hpp"
#include "vmass/core/driveline_mode.hpp"
#include "vmass/core/extraction.hpp"
#include "vmass/core/lag_estimator.hpp"
#include "vmass/core/low_pass_filter.hpp"
#include "vmass/core/overall_ratio_tracker.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/core/speed_refresh.hpp"
#include "vmass/core/speed_signal_scale.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass {

/// What the pair's acceleration change is measured with (see the header).
enum class AccelSource : std::uint8_t {
  kAccelerometer = 0,  ///< a_x: the grade cancels exactly; body pitch scales it by 1 + g k_pitch
  kWheelSpeed,         ///< the derivative of the wheel speed: no pitch; the ESC's radius error
  kCalibrated,         ///< a_x divided by its scale against the wheel speed, learned online
};
std::string_view accel_source_name(AccelSource s);

/// What the rotating term's change of the wheels' acceleration is measured with.
enum class RotatingAccelSource : std::uint8_t {
  kAuto = 0,       ///< the wheel speed until SpeedRefresh finds it coarse, then the accelerometer
  kWheelSpeed,     ///< the derivative of the wheel speed: it turns with the wheels
  kAccelerometer,  ///< a_x (pitch-corrected as the pair's own): for a coarse or late speed
};
std::string_view rotating_accel_source_name(RotatingAccelSource s);

struct LongitudinalParams {
  bool enabled = true;
  AccelSource accel_source = AccelSource::kAccelerometer;
  double scale_memory_s = 120.0;  ///< kCalibrated: memory of the scale, s of excited pairs
  RotatingAccelSource rotating_accel_source = RotatingAccelSource::kAuto;
  double max_abs_accel_y_mps2 = 0.5;
  double min_abs_delta_accel_x_mps2 = 0.02;  ///< floor of the excitation gate
  double min_abs_delta_force_n = 10.0;       ///< floor of the excitation gate
  double min_excitation_sigma = 3.0;
  double min_speed_mps = 2.0;
  double settle_s = 0.5;  ///< clean time before a window, after a brake or shift
  /// Clean time before a window after a gear change, when the force is an automatic's engine
  /// torque read through its converter map: the gearbox hands the torque over in its clutches,
  /// the engine's report does not show the dip, and the low-pass remembers the unseen dip for
  /// about a second (a pair whose window starts in it reads the mass low).
  double converter_shift_settle_s = 1.5;
  bool use_braking = false;
  /// Take pairs while a combustion engine is dragged (negative reported torque, overrun). An ECU
  /// reports its drag torque from a friction model, its least accurate figure (20-40 % off is
  /// common), so off by default. Regeneration (vehicle.electric_drive) is not overrun.
  bool use_overrun = false;
  double brake_applied_weight_fraction = 0.02;  ///< brakes count as applied above this K P / (M g)
  double noise_memory_s = 30.0;
  bool subtract_aero = true;
  double weight = 1.0;
  LagParams lag;
  DrivelineModeParams driveline_mode;

  std::string validate() const;
};

class LongitudinalExtractor {
 public:
  LongitudinalExtractor(const VehicleParams& vehicle, const LongitudinalParams& params,
                        const DifferencingParams& differencing);

  Extraction step(const Sample& sample);
  /// Pairs kept while the lag was unknown, one per call, at the identified lag (gated as in
  /// step()); false when none is left. Call after each step().
  bool pop_released(Extraction* out);
  /// Pairs held while the lag is unknown (those pop_released() will release).
  std::size_t pending_count() const { return pending_count_; }
  /// The i-th held pair (0: the oldest) at lag_s (in [0, max_lag_s]), gated as in step(). For a
  /// provisional estimate only: the pair that enters the belief is the one pop_released() gives
  /// once the lag is identified.
  Extraction provisional(std::size_t i, double lag_s) const;
  /// Forget the signal history and what forget_load() forgets (a restart: the load may have
  /// changed). A hole in the data (a tick step() cannot use) restarts only the history: the
  /// held pairs were complete before it.
  void reset();
  /// Another load, keeping the signal history: the lag's evidence of the load before stays only
  /// as a prior (LagEstimator::keep_as_prior), the held pairs and the noise scale are forgotten.
  /// Pooled over two loads they mislead: a truck's launch at 33 t after a drive at 18 t read the
  /// lag 0.003-0.012 s (0.03 on either load alone), and the noise, measured about the old mass,
  /// doubled.
  void forget_load();
  /// Take the lag's evidence and the noise scale of another extractor of the same block (the
  /// load monitor's, learnt on the new load alone).
  void take_load(const LongitudinalExtractor& other);
  /// The mass the noise scale and the gates use: the prior's, then the belief's (Pipeline).
  void set_reference_mass(double mass_kg) { reference_mass_kg_ = mass_kg; }

  const LagEstimator& lag() const { return lag_; }
  /// How often the speed signal changes (whether its derivative can carry the rotating term).
  const SpeedRefresh& speed_refresh() const { return speed_refresh_; }
  /// The rotating term reads the wheel speed's derivative now (else the accelerometer).
  bool rotating_from_wheel_speed() const;
  /// kCalibrated: the accelerometer's scale against the wheel speed, 1 + g k_pitch (1 otherwise).
  double accel_scale() const;
  /// Robust scale of the residual dF - M_ref da at the horizon, N.
  double force_noise_n() const { return residual_scale_n_ * kScalePerMeanAbs; }
  /// The same in acceleration, force_noise_n() / M_ref, m/s^2.
  double accel_noise_mps2() const { return force_noise_n() / reference_mass_kg_; }

  /// Inputs this block needs: a_x, speed and the wheel torque (vehicle.wheel_torque_input), or,
  /// on a car whose driveline ratios are configured, the engine torque and the gear (the engine
  /// speed, when present, detects a slipping converter or clutch), or, with
  /// vehicle.derive_overall_ratio, the engine torque and the engine speed (the ratio derived from
  /// them, OverallRatioTracker). Brake pressure or the brake switch decide the brake state when
  /// present.
  InputMask required_inputs() const { return required_; }

 private:
  static constexpr double kScalePerMeanAbs = 1.2533;  ///< sigma / E|r| of a normal residual

  struct Record {
    TimeUs time_us;
    double accel_x_mps2;
    double wheel_accel_mps2;
    double accel_y_mps2;
    double force_n;
    double converter_force_n;  ///< the converter's multiplication in force_n, N
    int gear;
    bool converter_multiplying;
  };
  struct TickInputs {
    double force_n = 0.0;
    double converter_force_n = 0.0;      ///< force_n's part from TR - 1 (ConverterMap)
    bool converter_multiplying = false;  ///< below the converter's coupling point (TR > 1)
    bool clean = false;                  ///< no brake, valid gear, fast enough
  };

  /// The filters and the differencing start again (no window spans a hole); held pairs stay.
  void restart_stretch();
  bool read(const Sample& s, TickInputs* in);
  /// C_wheel from the wheel torque, or from the engine torque through the gear; NaN if neither.
  double wheel_torque_nm(const Sample& s) const;
  /// How the engine's torque reaches the wheels: locked, through the converter's map, or
  /// slipping (the engine faster or slower than the wheels through the gear, unusable).
  /// The engine is read against the speed through the gear times the speed signal's learnt
  /// scale (SpeedSignalScale), which this also updates.
  ConverterReading coupling(const Sample& s);
  /// An automatic's gear change is still in the filtered force (converter_shift_settle_s).
  bool hidden_shift_in_window() const;
  /// The derived ratio (derive_overall_ratio) is locked on the previous tick's confirmed plateau.
  bool ratio_locked_on_plateau() const;
  /// What a pair's two ends must share: the gear, or the derived ratio's plateau (0: none).
  int gear_identity(const Sample& s) const;
  bool braking(const Sample& s);
  bool physically_possible(double force_n, const Sample& s) const;
  Record filtered_record(const Sample& s, const TickInputs& in);
  void update_noise(double residual_n);
  double initial_residual_scale_n() const;
  /// The pair's acceleration change from the configured source.
  double delta_accel(const Record& now, const Record& then) const;
  void update_scale(const Record& now, const Record& then);
  /// y at every candidate lag into y_by_lag_ (the filtered force L ticks earlier).
  void fill_y_by_lag(const Record& now, const Record& then);
  Extraction gate(const Record& now, const Record& then, Extraction out);
  /// What a pair needs besides its y: kept with it while the lag is unknown.
  struct PairTerms {
    TimeUs time_us = 0;
    double delta_accel_mps2 = 0.0;
    double noise_n = 0.0;                 ///< the gates' noise scale
    double pair_noise_n = 0.0;            ///< RegressionPair::noise_std_n
    double rotating_n = 0.0;              ///< RegressionPair::rotating_n
    double converter_n = 0.0;             ///< RegressionPair::converter_n
    int gear = 0;                         ///< RegressionPair::gear
    double rotating_mass_kg = 0.0;        ///< RegressionPair::rotating_mass_kg
    double wheel_delta_accel_mps2 = 0.0;  ///< RegressionPair::wheel_delta_accel_mps2
  };
  PairTerms pair_terms(const Record& now, const Record& then, double delta_accel) const;
  /// The force and plausibility gates of a pair whose differenced force is y.
  Extraction finish(const PairTerms& terms, double y, Extraction out) const;
  /// m_rot of the record's gear (or derived-ratio plateau), kg.
  double rotating_mass_kg(const Record& now) const;
  /// The change of the wheels' acceleration over the window, from that source.
  double rotating_delta_accel(const Record& now, const Record& then) const;
  /// m_rot(gear) times that change, N.
  double rotating_n(const Record& now, const Record& then) const;
  void keep_pending(const PairTerms& terms);

  VehicleParams vehicle_;
  LongitudinalParams params_;
  InputMask required_;
  double tick_rate_hz_;
  LowPassFilter accel_x_filter_, accel_y_filter_, force_filter_, converter_filter_, speed_filter_,
      brake_filter_;
  DifferencingHistory<Record> history_;
  DelayLine<double> filtered_force_;  ///< the last max_lag + window ticks of filtered force
  LagEstimator lag_;
  DrivelineMode mode_;  ///< kept through restarts and loads: a property of the vehicle
  std::vector<double> y_by_lag_;
  // Pairs awaiting the lag: a ring of their terms and their y at every lag.
  std::vector<PairTerms> pending_;
  std::vector<double> pending_y_;  ///< pending_.size() x y_by_lag_.size()
  std::size_t pending_count_ = 0;
  std::size_t pending_next_ = 0;  ///< next to release
  double reference_mass_kg_;
  double residual_scale_n_;
  double noise_forget_;
  double scale_forget_;
  double pitch_scale_;       ///< 1 + g k_pitch: the accelerometer's over-read of da from body pitch
  double scale_s_wi_ = 0.0;  ///< kCalibrated: sum of dv' da_x
  double scale_s_ii_ = 0.0;  ///< ... and of da_x^2
  long scale_pairs_ = 0;
  double previous_speed_ = 0.0;
  bool has_previous_speed_ = false;
  int previous_gear_ = 0;
  long clean_ticks_ = 0;
  long window_ticks_;
  long settle_ticks_;
  long converter_shift_settle_ticks_;
  long ticks_since_shift_ = 0;  ///< since the gear signal last changed
  // vehicle.derive_overall_ratio: the ratio and its plateaus (the gear) from the engine speed.
  bool derive_ratio_;
  OverallRatioTracker ratio_tracker_;
  ConverterMap converter_;
  SpeedSignalScale speed_scale_;
  SpeedRefresh speed_refresh_;  ///< kept through restarts: a property of the bus
};

}  // namespace vmass
