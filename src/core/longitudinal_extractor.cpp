#include "vmass/core/longitudinal_extractor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vmass/core/param_check.hpp"

namespace vmass {

namespace {
// Starting noise scale: a residual of this acceleration times the reference mass, m/s^2.
constexpr double kInitialNoiseMps2 = 0.02;
// A residual counts at most this many scales in the robust mean (one-sided Huber).
constexpr double kResidualClip = 3.0;
// The plausible band of the mass a pair implies, relative to the empty and maximum masses.
constexpr double kImpliedLowPerEmpty = 0.5;
constexpr double kImpliedHighPerMax = 1.5;
constexpr double kImpliedHighPerEmptyWithoutMax = 2.5;
// Beyond these no road vehicle goes (tyres give at most about 1.2 g; 360 km/h).
constexpr double kMaxAbsAccelMps2 = 20.0;
constexpr double kMaxSpeedMps = 100.0;
constexpr double kMaxForcePerWeight = 2.0;
// A pitch of k deg/g tilts the accelerometer by k a / g deg: it reads a (1 + k pi / 180).
constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;

InputMask torque_inputs(const VehicleParams& v) {
  if (v.derive_overall_ratio)
    return input_bit(Input::kEngineTorque) | input_bit(Input::kEngineSpeed);
  if (v.knows_driveline() && !v.wheel_torque_input) {
    return input_bit(Input::kEngineTorque) | input_bit(Input::kGear);
  }
  return input_bit(Input::kWheelTorque);
}
}  // namespace

std::string_view accel_source_name(AccelSource s) {
  switch (s) {
    case AccelSource::kAccelerometer:
      return "accelerometer";
    case AccelSource::kWheelSpeed:
      return "wheel_speed";
    case AccelSource::kCalibrated:
      return "calibrated";
  }
  return "unknown";
}

std::string_view rotating_accel_source_name(RotatingAccelSource s) {
  switch (s) {
    case RotatingAccelSource::kAuto:
      return "auto";
    case RotatingAccelSource::kWheelSpeed:
      return "wheel_speed";
    case RotatingAccelSource::kAccelerometer:
      return "accelerometer";
  }
  return "unknown";
}

std::string LongitudinalParams::validate() const {
  ParamCheck c("estimator.longitudinal");
  c.positive("max_abs_accel_y_mps2", max_abs_accel_y_mps2);
  c.non_negative("min_abs_delta_accel_x_mps2", min_abs_delta_accel_x_mps2);
  c.non_negative("min_abs_delta_force_n", min_abs_delta_force_n);
  c.non_negative("min_excitation_sigma", min_excitation_sigma);
  c.non_negative("min_speed_mps", min_speed_mps);
  c.non_negative("settle_s", settle_s);
  c.non_negative("converter_shift_settle_s", converter_shift_settle_s);
  c.in_open_range("brake_applied_weight_fraction", brake_applied_weight_fraction, 0.0, 1.0);
  c.positive("noise_memory_s", noise_memory_s);
  c.positive("scale_memory_s", scale_memory_s);
  c.positive("weight", weight);
  c.nested(lag.validate());
  c.nested(driveline_mode.validate());
  return c.message();
}

LongitudinalExtractor::LongitudinalExtractor(const VehicleParams& vehicle,
                                             const LongitudinalParams& params,
                                             const DifferencingParams& differencing)
    : vehicle_(vehicle),
      params_(params),
      required_(input_bit(Input::kAccelX) | input_bit(Input::kSpeed) | torque_inputs(vehicle)),
      tick_rate_hz_(differencing.tick_rate_hz),
      accel_x_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      accel_y_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      force_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      converter_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      speed_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      brake_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      history_(differencing),
      filtered_force_(
          static_cast<std::size_t>(differencing.steps()) + 1 +
          static_cast<std::size_t>(std::lround(params.lag.max_lag_s * differencing.tick_rate_hz))),
      lag_(params.lag, differencing.tick_rate_hz),
      mode_(params.driveline_mode, differencing.tick_rate_hz),
      y_by_lag_(static_cast<std::size_t>(lag_.max_lag_ticks()) + 1, 0.0),
      pending_(static_cast<std::size_t>(
                   std::ceil(params.lag.min_evidence_s * differencing.tick_rate_hz)) +
               1),
      pending_y_(pending_.size() * y_by_lag_.size(), 0.0),
      reference_mass_kg_(vehicle.empty_mass_kg),
      residual_scale_n_(initial_residual_scale_n()),
      noise_forget_(std::exp(-1.0 / (params.noise_memory_s * differencing.tick_rate_hz))),
      scale_forget_(std::exp(-1.0 / (params.scale_memory_s * differencing.tick_rate_hz))),
      pitch_scale_(1.0 + vehicle.pitch_gradient_deg_per_g * kRadPerDeg),
      window_ticks_(differencing.steps()),
      settle_ticks_(std::lround(params.settle_s * differencing.tick_rate_hz)),
      converter_shift_settle_ticks_(
          std::lround(params.converter_shift_settle_s * differencing.tick_rate_hz)),
      derive_ratio_(vehicle.derive_overall_ratio),
      ratio_tracker_(vehicle, RatioTrackerParams{}, differencing.tick_rate_hz),
      converter_(vehicle),
      speed_scale_(SpeedSignalScaleParams{}, vehicle.torque_converter) {}

void LongitudinalExtractor::reset() {
  restart_stretch();
  forget_load();
}

void LongitudinalExtractor::forget_load() {
  lag_.keep_as_prior();
  pending_count_ = 0;
  pending_next_ = 0;
  residual_scale_n_ = initial_residual_scale_n();
}

double LongitudinalExtractor::initial_residual_scale_n() const {
  return kInitialNoiseMps2 * vehicle_.empty_mass_kg / kScalePerMeanAbs;
}

void LongitudinalExtractor::take_load(const LongitudinalExtractor& other) {
  lag_ = other.lag_;
  residual_scale_n_ = other.residual_scale_n_;
}

void LongitudinalExtractor::restart_stretch() {
  history_.clear();
  filtered_force_.clear();
  accel_x_filter_.reset();
  accel_y_filter_.reset();
  force_filter_.reset();
  converter_filter_.reset();
  speed_filter_.reset();
  brake_filter_.reset();
  ratio_tracker_.restart();
  mode_.restart();
  has_previous_speed_ = false;
  clean_ticks_ = 0;
}

bool LongitudinalExtractor::braking(const Sample& s) {
  if (s.has(Input::kBrakePressure) && vehicle_.brake_gain_n_per_pa > 0.0) {
    // Decided on the low-passed pressure: a sensor's noise around zero (a few kPa, enough on a
    // truck's air brakes) must not flicker the brakes on and cut every clean stretch short.
    const double pressure_pa = brake_filter_.step(s.brake_pressure_pa);
    const double weight_n = vehicle_.empty_mass_kg * vehicle_.gravity_mps2;
    return pressure_pa * vehicle_.brake_gain_n_per_pa >
           params_.brake_applied_weight_fraction * weight_n;
  }
  if (s.has(Input::kBrakeSwitch)) return s.brake_switch;
  // Neither signal: only a clearly positive drive torque rules the brakes out.
  return !(s.wheel_torque_nm > 0.0);
}

double LongitudinalExtractor::wheel_torque_nm(const Sample& s) const {
  if (s.has(Input::kWheelTorque)) return s.wheel_torque_nm;
  if (derive_ratio_ && s.has(Input::kEngineTorque)) {
    return ratio_tracker_.wheel_torque_nm(s.engine_torque_nm);
  }
  if (s.has(Input::kEngineTorque) && s.has(Input::kGear)) {
    return vehicle_.wheel_torque_from_engine_nm(s.engine_torque_nm, s.gear);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

ConverterReading LongitudinalExtractor::coupling(const Sample& s) {
  ConverterReading locked;
  locked.coupling = DrivelineCoupling::kLocked;
  if (!vehicle_.knows_driveline() || !s.has(Input::kEngineSpeed) || !s.has(Input::kGear)) {
    return locked;  // nothing to check it by
  }
  const double through_gear_radps =
      std::abs(s.speed_mps) / vehicle_.wheel_radius_m * vehicle_.overall_ratio(s.gear);
  if (s.gear > 0 && s.gear == previous_gear_) {
    speed_scale_.observe(s.engine_speed_radps, through_gear_radps, s.speed_mps);
  }
  return converter_.read(s.engine_speed_radps, through_gear_radps * speed_scale_.scale());
}

// Only an automatic's engine torque read through its map: a wheel torque or a clutch gearbox's
// engine report shows the shift's dip, and the plain settle suffices there.
bool LongitudinalExtractor::hidden_shift_in_window() const {
  return vehicle_.knows_converter_map() && !derive_ratio_ && !vehicle_.wheel_torque_input &&
         ticks_since_shift_ < window_ticks_ + converter_shift_settle_ticks_;
}

// The derived ratio's "same gear": locked on a confirmed plateau, the previous tick's.
bool LongitudinalExtractor::ratio_locked_on_plateau() const {
  const RatioReading& r = ratio_tracker_.reading();
  return r.locked && r.confirmed && r.plateau == previous_gear_;
}

int LongitudinalExtractor::gear_identity(const Sample& s) const {
  if (derive_ratio_) return ratio_tracker_.reading().plateau;
  return s.has(Input::kGear) ? s.gear : 0;
}

// Values no car produces (a spike, a wrong scale) are a hole in the data, as NaN is: through the
// low-pass one such tick would spread over seconds of pairs.
bool LongitudinalExtractor::physically_possible(double force_n, const Sample& s) const {
  const double heaviest_kg = std::isfinite(vehicle_.max_mass_kg)
                                 ? vehicle_.max_mass_kg
                                 : kImpliedHighPerEmptyWithoutMax * vehicle_.empty_mass_kg;
  return std::abs(s.accel_x_mps2) <= kMaxAbsAccelMps2 && std::abs(s.speed_mps) <= kMaxSpeedMps &&
         std::abs(force_n) <= kMaxForcePerWeight * heaviest_kg * vehicle_.gravity_mps2;
}

// The tick's force and whether the tick is clean (see the header). False: not usable at all.
bool LongitudinalExtractor::read(const Sample& s, TickInputs* in) {
  if (!s.has_all(required_)) return false;
  if (derive_ratio_) ratio_tracker_.step(s.engine_speed_radps, s.speed_mps);
  const double r = vehicle_.wheel_radius_m;
  const ConverterReading converter = derive_ratio_ ? ConverterReading{} : coupling(s);
  const bool multiplied = converter.coupling == DrivelineCoupling::kConverter;
  // A wheel torque holds the converter's multiplication already, by the TCU's model of it (the
  // map's, with the map's error); an engine torque gets it from the map here.
  const bool after_converter = s.has(Input::kWheelTorque);
  const double torque_force = wheel_torque_nm(s) / r;
  double force =
      multiplied && !after_converter ? torque_force * converter.torque_ratio : torque_force;
  const double force_n_reported = force;
  const bool brakes = braking(s);
  // The brake force is subtracted wherever the pressure is known: below the "applied" level it
  // is small, and its gain's error with it, but it is not zero (a brake released inside a window
  // would otherwise read as unexplained acceleration).
  if (s.has(Input::kBrakePressure)) force -= s.brake_pressure_pa * vehicle_.brake_gain_n_per_pa;
  if (params_.subtract_aero && vehicle_.drag_area_m2 > 0.0) {
    force -= 0.5 * vehicle_.air_density_kg_per_m3 * vehicle_.drag_area_m2 * s.speed_mps *
             std::abs(s.speed_mps);
  }
  if (!physically_possible(force, s)) return false;
  // A wheel torque is its ECU's reading whatever the clutch or converter does, as it was before
  // the engine speed was read; an engine torque does not reach the wheels through a slip.
  const bool driveline_ok = after_converter || converter.coupling != DrivelineCoupling::kSlipping;
  const bool gear_ok =
      derive_ratio_
          ? ratio_locked_on_plateau()
          : (!s.has(Input::kGear) || (s.gear > 0 && s.gear == previous_gear_)) && driveline_ok;
  const bool shifted = s.has(Input::kGear) && s.gear != previous_gear_;
  ticks_since_shift_ = shifted ? 0 : ticks_since_shift_ + 1;
  previous_gear_ = gear_identity(s);
  const bool clean = (!brakes || params_.use_braking) &&
                     (force_n_reported >= 0.0 || vehicle_.electric_drive || params_.use_overrun) &&
                     gear_ok && std::abs(s.speed_mps) >= params_.min_speed_mps;
  // A car that sends no gear is taken as one gear (a single-speed electric drive, mostly).
  const int mode_gear = s.has(Input::kGear) || derive_ratio_ ? previous_gear_ : 1;
  mode_.observe(force_n_reported, s.accel_x_mps2, mode_gear, clean);
  in->force_n = force - force_n_reported + mode_.hub_force_n(force_n_reported, mode_gear);
  // The multiplication's part of the force: the engine's times TR - 1.
  in->converter_force_n = 0.0;
  if (multiplied) {
    const double tr = converter.torque_ratio;
    in->converter_force_n = (after_converter ? torque_force / tr : torque_force) * (tr - 1.0);
  }
  in->converter_multiplying = multiplied && converter.torque_ratio > 1.0;
  in->clean = clean;
  return true;
}

LongitudinalExtractor::Record LongitudinalExtractor::filtered_record(const Sample& s,
                                                                     const TickInputs& in) {
  speed_refresh_.observe(s.time_us, s.speed_mps);
  const double speed = speed_filter_.step(s.speed_mps);
  const double wheel_accel = has_previous_speed_ ? (speed - previous_speed_) * tick_rate_hz_ : 0.0;
  previous_speed_ = speed;
  has_previous_speed_ = true;
  const double ay = s.has(Input::kAccelY) && std::isfinite(s.accel_y_mps2) ? s.accel_y_mps2 : 0.0;
  return Record{s.time_us, accel_x_filter_.step(s.accel_x_mps2), wheel_accel,
                accel_y_filter_.step(ay), force_filter_.step(in.force_n),
                // Zero without a map: no filter to run on every tick.
                vehicle_.knows_converter_map() ? converter_filter_.step(in.converter_force_n) : 0.0,
                gear_identity(s), in.converter_multiplying};
}

void LongitudinalExtractor::update_noise(double residual_n) {
  const double clipped = std::min(std::abs(residual_n), kResidualClip * residual_scale_n_);
  residual_scale_n_ = noise_forget_ * residual_scale_n_ + (1.0 - noise_forget_) * clipped;
}

double LongitudinalExtractor::rotating_mass_kg(const Record& now) const {
  if (derive_ratio_) return ratio_tracker_.rotating_mass_kg(now.gear);
  const double gear_kg = vehicle_.rotating_mass_for_gear(now.gear, now.gear > 0);
  return now.converter_multiplying
             ? converter_.unlocked_rotating_mass_kg(gear_kg, vehicle_.rotating_mass_kg)
             : gear_kg;
}

bool LongitudinalExtractor::rotating_from_wheel_speed() const {
  switch (params_.rotating_accel_source) {
    case RotatingAccelSource::kWheelSpeed:
      return true;
    case RotatingAccelSource::kAccelerometer:
      return false;
    case RotatingAccelSource::kAuto:
      break;
  }
  return !speed_refresh_.coarse();
}

double LongitudinalExtractor::rotating_delta_accel(const Record& now, const Record& then) const {
  if (rotating_from_wheel_speed()) return now.wheel_accel_mps2 - then.wheel_accel_mps2;
  // The body moves with the wheels while they grip; its pitch is taken out as the pair's own is.
  const double imu = now.accel_x_mps2 - then.accel_x_mps2;
  return params_.accel_source == AccelSource::kCalibrated ? imu / accel_scale()
                                                          : imu / pitch_scale_;
}

double LongitudinalExtractor::rotating_n(const Record& now, const Record& then) const {
  return rotating_mass_kg(now) * rotating_delta_accel(now, then);
}

void LongitudinalExtractor::fill_y_by_lag(const Record& now, const Record& then) {
  const double rotating_n = this->rotating_n(now, then);
  const std::size_t window = static_cast<std::size_t>(window_ticks_);
  const std::size_t available = filtered_force_.size();
  for (std::size_t lag = 0; lag < y_by_lag_.size(); ++lag) {
    // Until enough history is kept, the longest available lag stands in.
    const std::size_t l = std::min(lag, available - 1 - window);
    y_by_lag_[lag] = filtered_force_.ago(l) - filtered_force_.ago(l + window) - rotating_n;
  }
}

double LongitudinalExtractor::accel_scale() const {
  // Used once a few seconds of excited pairs have been seen.
  constexpr long kMinScalePairs = 300;
  if (params_.accel_source != AccelSource::kCalibrated || scale_pairs_ < kMinScalePairs ||
      !(scale_s_wi_ > 0.0)) {
    return 1.0;
  }
  // da_x regressed on dv' would be attenuated by the wheel-speed derivative's noise (a speed
  // signal's steps and slip): -9.8 % on the population. The reverse regression, dv' on da_x, is
  // not: the filtered accelerometer's noise is the smaller. scale = sum da_x^2 / sum dv' da_x.
  return scale_s_ii_ / scale_s_wi_;
}

double LongitudinalExtractor::delta_accel(const Record& now, const Record& then) const {
  const double wheel = now.wheel_accel_mps2 - then.wheel_accel_mps2;
  const double imu = now.accel_x_mps2 - then.accel_x_mps2;
  switch (params_.accel_source) {
    case AccelSource::kWheelSpeed:
      return wheel;
    case AccelSource::kCalibrated:  // the learned scale holds the pitch too
      return imu / accel_scale();
    case AccelSource::kAccelerometer:
      break;
  }
  return imu / pitch_scale_;
}

// The accelerometer's change against the wheel speed's over excited pairs: the slope kappa of
// (da_x - dv') on dv' (grade changes are noise to it, pitch and the ESC's radius error are not).
void LongitudinalExtractor::update_scale(const Record& now, const Record& then) {
  const double wheel = now.wheel_accel_mps2 - then.wheel_accel_mps2;
  const double imu = now.accel_x_mps2 - then.accel_x_mps2;
  scale_s_wi_ = scale_forget_ * scale_s_wi_ + wheel * imu;
  scale_s_ii_ = scale_forget_ * scale_s_ii_ + imu * imu;
  ++scale_pairs_;
}

Extraction LongitudinalExtractor::gate(const Record& now, const Record& then, Extraction out) {
  if (std::max(std::abs(now.accel_y_mps2), std::abs(then.accel_y_mps2)) >=
      params_.max_abs_accel_y_mps2) {
    out.verdict = PairVerdict::kLateralAccel;
    return out;
  }
  const double delta_accel = this->delta_accel(now, then);
  const double noise_n = force_noise_n();
  const double min_force =
      std::max(params_.min_abs_delta_force_n, params_.min_excitation_sigma * noise_n);
  if (std::abs(delta_accel) * reference_mass_kg_ <=
      std::max(params_.min_abs_delta_accel_x_mps2 * reference_mass_kg_, min_force)) {
    out.verdict = PairVerdict::kSmallDeltaAccel;
    return out;
  }
  if (params_.accel_source == AccelSource::kCalibrated) update_scale(now, then);
  lag_.add(delta_accel, y_by_lag_.data());
  const PairTerms terms = pair_terms(now, then, delta_accel);
  if (!lag_.identified()) {
    keep_pending(terms);
    out.verdict = PairVerdict::kAwaitingLag;
    return out;
  }
  return finish(terms, lag_.y_at_lag(y_by_lag_.data()), out);
}

// The pair's own noise: the measured residual scale and, in quadrature, what the rotating mass's
// uncertainty makes of its term (large in low gears) and the converter map's of its
// multiplication (the converter's part of dF, at the pair's own ends).
LongitudinalExtractor::PairTerms LongitudinalExtractor::pair_terms(const Record& now,
                                                                   const Record& then,
                                                                   double delta_accel) const {
  PairTerms t;
  t.time_us = now.time_us;
  t.delta_accel_mps2 = delta_accel;
  t.noise_n = force_noise_n();
  t.rotating_n = rotating_n(now, then);
  t.converter_n = now.converter_force_n - then.converter_force_n;
  t.pair_noise_n = std::hypot(t.noise_n, vehicle_.rotating_mass_accuracy_fraction * t.rotating_n,
                              vehicle_.torque_converter_map_accuracy_fraction * t.converter_n);
  t.gear = now.gear;
  t.rotating_mass_kg = rotating_mass_kg(now);
  t.wheel_delta_accel_mps2 = rotating_delta_accel(now, then);
  return t;
}

Extraction LongitudinalExtractor::finish(const PairTerms& terms, double y, Extraction out) const {
  const double min_force =
      std::max(params_.min_abs_delta_force_n, params_.min_excitation_sigma * terms.noise_n);
  if (std::abs(y) <= min_force) {
    out.verdict = PairVerdict::kSmallDeltaForce;
    return out;
  }
  const double delta_accel = terms.delta_accel_mps2;
  const double implied_kg = y / delta_accel;
  const double high = std::isfinite(vehicle_.max_mass_kg)
                          ? kImpliedHighPerMax * vehicle_.max_mass_kg
                          : kImpliedHighPerEmptyWithoutMax * vehicle_.empty_mass_kg;
  if (!(implied_kg >= kImpliedLowPerEmpty * vehicle_.empty_mass_kg && implied_kg <= high)) {
    out.verdict = PairVerdict::kImplausible;
    return out;
  }
  out.verdict = PairVerdict::kAccepted;
  out.pair.time_us = terms.time_us;
  out.pair.block = Block::kLongitudinal;
  out.pair.delta_accel_mps2 = delta_accel;
  out.pair.y_n = y;
  out.pair.weight = params_.weight;
  out.pair.noise_std_n = terms.pair_noise_n;
  out.pair.rotating_n = terms.rotating_n;
  out.pair.converter_n = terms.converter_n;
  out.pair.gear = terms.gear;
  out.pair.rotating_mass_kg = terms.rotating_mass_kg;
  out.pair.wheel_delta_accel_mps2 = terms.wheel_delta_accel_mps2;
  return out;
}

void LongitudinalExtractor::keep_pending(const PairTerms& terms) {
  // A full ring drops its oldest pair (the lag takes that long only when pairs are poor).
  const std::size_t slot = (pending_next_ + pending_count_) % pending_.size();
  if (pending_count_ < pending_.size()) {
    ++pending_count_;
  } else {
    pending_next_ = (pending_next_ + 1) % pending_.size();
  }
  pending_[slot] = terms;
  std::copy(y_by_lag_.begin(), y_by_lag_.end(),
            pending_y_.begin() + static_cast<std::ptrdiff_t>(slot * y_by_lag_.size()));
}

bool LongitudinalExtractor::pop_released(Extraction* out) {
  if (!lag_.identified() || pending_count_ == 0) return false;
  const double* y = pending_y_.data() + pending_next_ * y_by_lag_.size();
  *out = finish(pending_[pending_next_], lag_.y_at_lag(y), Extraction{});
  pending_next_ = (pending_next_ + 1) % pending_.size();
  --pending_count_;
  return true;
}

Extraction LongitudinalExtractor::provisional(std::size_t i, double lag_s) const {
  if (i >= pending_count_) return Extraction{};
  const std::size_t slot = (pending_next_ + i) % pending_.size();
  const double* y = pending_y_.data() + slot * y_by_lag_.size();
  return finish(pending_[slot], lag_.y_at(y, lag_s), Extraction{});
}

Extraction LongitudinalExtractor::step(const Sample& s) {
  Extraction out;
  if (!params_.enabled) {
    out.verdict = PairVerdict::kDisabled;
    return out;
  }
  TickInputs in;
  if (!read(s, &in)) {
    restart_stretch();  // a hole in the data: never difference across it
    out.verdict = s.has_all(required_) ? PairVerdict::kNonFinite : PairVerdict::kInputsInvalid;
    return out;
  }
  clean_ticks_ = in.clean ? clean_ticks_ + 1 : 0;
  const Record now = filtered_record(s, in);
  filtered_force_.push(now.force_n);
  const Record* then = history_.push_and_get_then(now, &out.verdict);
  if (then == nullptr) return out;
  if (clean_ticks_ < window_ticks_ + settle_ticks_ || (in.clean && hidden_shift_in_window())) {
    out.verdict = in.clean ? PairVerdict::kSettling : PairVerdict::kNotClean;
    return out;
  }
  fill_y_by_lag(now, *then);
  update_noise(lag_.y_at_lag(y_by_lag_.data()) - reference_mass_kg_ * delta_accel(now, *then));
  return gate(now, *then, out);
}

}  // namespace vmass
