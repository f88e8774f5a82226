// Realism: which real-world effects a simulation includes. Each effect's parameters live with
// the vehicle (TrueVehicle) or the scenario (road, wind, payload); this set only switches them on
// or off, so that one vehicle can be simulated with every effect, with none (the "kind"
// simulator of the named demo scenarios) or with one at a time (the ablation table of
// docs/accuracy.md).
//
// Where each effect acts:
//   driveline     the hub torque is not the ECU's reported torque (mode, lag, converter, drag,
//                 accessories, creep); regenerative braking; ABS and ESC
//   IMU           the accelerometer's own filter, bias and drift, noise, vibration, mounting,
//                 body pitch and roll
//   resistances   wind, rolling resistance growing with speed, driveline viscous losses
//   sensors       wheel slip and radius error in the speed, brake pressure offset and fade,
//                 per-ECU cycle times and latencies
//   knowledge     the empty mass, payload positions and the datasheet values differ from the
//                 truth (applied by the population's config writer and payload placement)
//
// Plain value type; thread-safe to copy and read.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vmass::sim {

enum class Effect : std::uint8_t {
  kDrivelineMode = 0,  ///< lightly damped torsional mode between reported and hub torque
  kDrivelineLag,       ///< the hub torque lags the report (actuation and computation delay)
  kTorqueConverter,    ///< automatic: multiplication when unlocked, the ECU's model is off
  kEngineDrag,         ///< overrun drag torque, reported with an error
  kAccessoryLoads,     ///< A/C compressor switching, left out of the reported torque
  kCreep,              ///< automatic: creep torque at low speed
  kRegenBraking,       ///< electric: negative wheel torque without brake pressure
  kAbsEsc,             ///< friction-limited braking (ABS) and ESC brake interventions
  kImuFilter,          ///< the accelerometer's own low-pass
  kImuBiasDrift,       ///< bias and random-walk drift
  kSensorNoise,        ///< white noise on every sensor signal
  kImuVibration,       ///< 8-25 Hz vibration growing with speed and roughness, engine orders
  kImuMounting,        ///< misalignment and a lever arm away from the centre of gravity
  kBodyPitchRoll,      ///< body pitch and roll per g tilt the accelerometer
  kWind,               ///< mean head and cross wind, gusts
  kSpeedResistance,    ///< rolling resistance growing with v^2, driveline viscous losses
  kWheelSpeed,         ///< speed from the wheels: slip, radius error, quantisation, display
  kBrakeSensor,        ///< pressure sensor offset
  kBrakeFade,          ///< brake gain falls with disc temperature
  kRoadRoughness,      ///< rough surface and speed bumps
  kBusTiming,          ///< each ECU's cycle time, phase and filter latency
  kMassUncertainty,    ///< the true empty mass is not the datasheet's (fuel, options)
  kPayloadPosition,    ///< payload where people put it (seats, boot), not at the CG
  kDatasheetErrors,    ///< the engineer's config values carry realistic errors
  kCount
};

constexpr int kEffectCount = static_cast<int>(Effect::kCount);

/// Stable snake_case name ("driveline_mode", ...), as in the ablation table and on the CLI.
std::string_view effect_name(Effect e);
/// One line saying what the effect is.
std::string_view effect_description(Effect e);
std::optional<Effect> parse_effect(std::string_view name);
std::vector<Effect> all_effects();

class Realism {
 public:
  /// No effect: the simulator as the demo scenarios use it.
  static Realism none() { return Realism(0); }
  static Realism all() { return Realism((std::uint32_t{1} << kEffectCount) - 1); }
  static Realism only(Effect e) { return none().with(e); }

  bool has(Effect e) const { return (bits_ & bit(e)) != 0; }
  Realism with(Effect e) const { return Realism(bits_ | bit(e)); }
  Realism without(Effect e) const { return Realism(bits_ & ~bit(e)); }
  bool any() const { return bits_ != 0; }
  std::uint32_t bits() const { return bits_; }

  /// "all", "none" or the names joined with '+'.
  std::string describe() const;
  /// Parses describe()'s forms, and "all-NAME" (everything but one effect). Empty on error.
  static std::optional<Realism> parse(std::string_view text);

  friend bool operator==(Realism a, Realism b) { return a.bits_ == b.bits_; }
  friend bool operator!=(Realism a, Realism b) { return a.bits_ != b.bits_; }

 private:
  explicit Realism(std::uint32_t bits) : bits_(bits) {}
  static std::uint32_t bit(Effect e) { return std::uint32_t{1} << static_cast<unsigned>(e); }
  std::uint32_t bits_ = 0;
};

}  // namespace vmass::sim
