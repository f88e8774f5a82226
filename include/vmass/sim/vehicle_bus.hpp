// VehicleBus: the CAN bus of a population vehicle. It writes the vehicle's own DBC (its
// identifiers, byte order, units, scaling and sign conventions drawn in CanConventions, only the
// signals the vehicle has), the `can:` mapping its engineer writes for that DBC, and the frames
// its ECUs send during a simulated drive.
//
// Frames: each message is sampled by its ECU at its own cycle time and phase, from the
// simulator's EcuSignals trace (1 kHz) at the sample time minus the message's latency
// (bus_timing; without it every message is sampled every 10 ms at the same instant, with no
// latency). Each transmitted value gets its white noise (sensor_noise), the paper's wheel-force
// noise set on the torque (eps, as r * eps), the ECU's torque scale error, and the DBC's
// quantisation. Every message carries a 4-bit rolling counter and an XOR checksum byte, as real
// buses do. Faults (missing, frozen or absurd messages, bursts of unknown or malformed frames)
// are injected at the frame level for the sensor-fault scenario.
//
// Logical messages: powertrain (wheel torque, per axle, or engine torque and speed; gear),
// dynamics (a_x; a_y and yaw rate when the car has them), speed (the ESC's), brake (pressure
// when present; the brake-light switch always), steering, level (rear ride height, optionally
// multiplexed with the front corners), cluster (displayed speed, odometer), and a few messages
// of other ECUs the estimator does not use.
//
// Not thread-safe per instance (a compiled decoder is read-only, the encoding is const).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vmass/can/can_frame.hpp"
#include "vmass/can/decoder.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/sensor_model.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::sim {

/// A fault injected on the bus (sensor_faults scenario).
struct BusFault {
  enum class Kind : std::uint8_t {
    kMissing,         ///< the message is not sent during the window
    kFrozen,          ///< its values stay at the window's start (the counter keeps rolling)
    kAbsurd,          ///< one frame with the signal at its largest raw value
    kUnknownBurst,    ///< frames with identifiers the DBC does not know
    kMalformedBurst,  ///< the message sent with 2 bytes instead of its length
  };
  Kind kind = Kind::kMissing;
  std::string message;  ///< logical name: powertrain, dynamics, speed, brake, steering, level
  double start_s = 0.0;
  double duration_s = 1.0;
};

struct BusOptions {
  Realism realism = Realism::all();
  std::uint64_t seed = 1;            ///< noise streams
  NoiseSet eps = NoiseSet::kNone;    ///< the paper's wheel-force noise on the torque signal
  double torque_report_scale = 1.0;  ///< the ECU's torque reads this x its own estimate
  std::vector<BusFault> faults;
};

class VehicleBus {
 public:
  explicit VehicleBus(const DrawnVehicle& vehicle);

  /// "" when the DBC compiled (it always should: a failure is a bug, reported with the reason).
  const std::string& error() const { return error_; }
  const std::string& dbc_text() const { return dbc_text_; }
  /// The config's `can:` section for dbc_file (YAML, top-level key `can`).
  std::string can_config_yaml(const std::string& dbc_file) const;
  /// The drive's frames in time order. "" or a message.
  std::string encode(const SimulationResult& result, const BusOptions& options,
                     std::vector<can::CanFrame>* frames) const;

  struct Signal;
  struct Message;

 private:
  void build_messages();
  void build_dbc();

  DrawnVehicle vehicle_;
  std::vector<Message> messages_;
  std::string dbc_text_;
  std::vector<can::Decoder> decoder_;  ///< 0 or 1 (no default constructor)
  std::string error_;
};

/// One signal of a population DBC and how it relates to the EcuSignals.
struct VehicleBus::Signal {
  enum class Source : std::uint8_t {
    kWheelTorque,
    kWheelTorqueFront,
    kWheelTorqueRear,
    kEngineTorque,
    kEngineSpeed,
    kGear,
    kAccelX,
    kAccelY,
    kYawRate,
    kSpeed,
    kBrakePressure,
    kBrakeSwitch,
    kSteering,
    kLevelRearRight,
    kLevelOther,
    kDisplaySpeed,
    kOdometer,
    kMuxPage,
    kFiller,  ///< other ECUs' content
  };
  Source source = Source::kFiller;
  std::string name;
  int byte = 0;     ///< first payload byte
  int length = 16;  ///< bits (byte-aligned: 4, 8, 16 or 32)
  bool is_signed = true;
  double factor = 1.0;
  double offset = 0.0;
  std::string unit;
  double minimum = 0.0, maximum = 0.0;
  double si_per_unit = 1.0;  ///< SI per DBC physical unit (the unit's scale)
  double sign = 1.0;         ///< -1: the DBC's positive direction is opposite to ISO 8855
  int mux = -1;              ///< page (>= 0) of a multiplexed signal; -1 plain
  bool is_switch = false;
  std::string input;  ///< the estimator input the engineer maps it to ("" none)
};

struct VehicleBus::Message {
  std::string logical;  ///< powertrain, dynamics, ...
  std::string name;
  std::uint32_t id = 0;
  bool extended = false;
  int length = 8;
  double period_s = 0.01;
  double latency_s = 0.0;
  double phase_s = 0.0;
  bool protected_frame = true;  ///< counter in byte 7 (low nibble), XOR checksum in byte 6
  std::vector<Signal> signals;
};

}  // namespace vmass::sim
