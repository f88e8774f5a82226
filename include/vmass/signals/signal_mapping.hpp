// SignalMapping: the config's `can:` section resolved against the DBC, i.e. which DBC signal(s)
// feed each estimator input and how their values become SI (see docs/signal-mapping.md).
//
//   can:
//     dbc: vehicle.dbc                  # required; relative to the config file
//     inputs:                           # input name (vmass::input_name) -> mapping; absent inputs
//       speed:                          #   stay invalid
//         message: ESP_Speed            # required: BO_ name
//         signal: VehicleSpeed          # required: SG_ name in that message
//         mux: 1                        # required for (and only for) a multiplexed signal: the
//                                       #   raw value of its multiplexor switch to accept
//         unit: km/h                    # optional: overrides the DBC's unit string
//         gain: 1.0                     # optional, != 0: multiplies the SI value (a sign flip, a
//                                       #   ratio); with an unknown or missing unit it is the
//                                       #   whole conversion from the DBC value to SI
//         offset: 0.0                   # optional: added last, SI
//         timeout_s: 0.05               # optional, > 0: stale when older; default 5 x the
//                                       #   message's GenMsgCycleTime, 0.1 s without one
//       wheel_torque:                   # a sum of signals (e.g. a torque per axle); every term
//         sum:                          #   takes message, signal, mux, unit, gain
//           - {message: PT_Torque, signal: Front}
//           - {message: EDU_Rear, signal: Torque, gain: 1.0}
//         offset: 0.0                   # optional, SI, added to the sum
//         timeout_s: 0.05               # optional, for every term (default: per term's message)
//     enforce_dbc_ranges: false         # refuse values outside [min|max] (real files lie)
//     e2e: {...}                        # alive counters and checksums (message_protection.hpp)
//     plausibility: {...}               # physical checks (plausibility_params.hpp)
//
// One term:   si = dbc_physical * unit_scale * gain      (unit_scale from units.hpp)
// One input:  value = sum over terms of si + offset
//
// Config errors ("file:line: can.inputs.speed.signal: ...") name the key: unknown keys or input
// names, a missing message or signal, a multiplexed signal without mux (or a mux value that does
// not select it, or mux on a plain signal), a unit that is not in the table without a gain, a
// unit of the wrong dimension for the input (km/h on accel_x), gain 0, timeout_s <= 0.
//
// Configuration time only (allocates, parses); not thread-safe. A SignalMapping is a plain
// value.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "vmass/can/decoder.hpp"
#include "vmass/config/config.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/signals/message_protection.hpp"
#include "vmass/signals/plausibility_params.hpp"

namespace vmass::signals {

/// One DBC signal feeding an input.
struct MappedSignal {
  std::string message;  ///< names, for reports
  std::string signal;
  can::SignalRef ref;
  can::SignalRef mux_switch;    ///< the multiplexor switch to check; invalid when not muxed
  std::uint64_t mux_value = 0;  ///< raw switch value accepted
  std::string unit;             ///< the unit used (the DBC's, or the config's override)
  double unit_scale = 1.0;      ///< DBC physical -> SI (1 for an unknown unit with a gain)
  double gain = 1.0;
  bool has_range = false;  ///< DBC [min|max] (physical), checked on every frame
  double minimum = 0.0;
  double maximum = 0.0;
  int cycle_time_ms = 0;   ///< the message's GenMsgCycleTime (0: none)
  double timeout_s = 0.1;  ///< effective timeout

  /// SI value per DBC physical value.
  double scale() const { return unit_scale * gain; }
};

struct InputMapping {
  Input input = Input::kSpeed;
  bool is_sum = false;
  std::vector<MappedSignal> terms;  ///< one for a plain mapping
  double offset = 0.0;              ///< SI, added to the sum
};

struct SignalMapping {
  std::vector<InputMapping> inputs;  ///< mapped inputs in Input order
  MessageProtection protection;      ///< can.e2e: alive counters and checksums
  bool enforce_dbc_ranges = false;   ///< can.enforce_dbc_ranges: refuse values outside [min|max]
  PlausibilityParams plausibility;   ///< can.plausibility: physical limits, cross-checks

  /// The mapping of an input, or nullptr when it is not mapped.
  const InputMapping* find(Input input) const;
  /// One line per input: "speed <- ESP_Speed.VehicleSpeed [km/h x 0.2778] timeout 0.05 s".
  std::string describe() const;
};

/// Resolves `can.inputs` (the node may be null: nothing mapped). `file` names the config in
/// errors, `dbc_name` the DBC. Returns "" and fills *out, or "file:line: key: message".
std::string parse_signal_mapping(const YAML::Node& inputs, const std::string& file,
                                 const can::Decoder& decoder, const std::string& dbc_name,
                                 SignalMapping* out);

/// Everything a CAN front end needs from the config: the compiled DBC and the mapping.
struct CanInputs {
  std::shared_ptr<const can::Decoder> decoder;
  SignalMapping mapping;
  std::string dbc_path;               ///< resolved against the config's directory
  std::vector<std::string> warnings;  ///< DBC deviations, "file:line:column: warning: ..."
};

struct CanInputsLoad {
  std::optional<CanInputs> inputs;
  std::string error;  ///< "file:line: can.key: message" when inputs is empty
  bool ok() const { return inputs.has_value(); }
};

/// Reads the config's `can:` section: loads and compiles `can.dbc`, resolves `can.inputs`,
/// `can.e2e`, `can.enforce_dbc_ranges` and `can.plausibility`. A missing section, an unreadable
/// DBC or a DBC with errors is an error naming can.dbc.
CanInputsLoad load_can_inputs(const Config& config);

}  // namespace vmass::signals
