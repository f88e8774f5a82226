// Units: DBC unit strings and their conversion to the SI units of vmass::Sample.
//
//     si_value = dbc_physical_value * scale          (every unit in the table is a pure scale)
//
// Matching ignores case and spaces, and accepts the degree sign in UTF-8 or cp1252. The table
// (unit_table() lists it; docs/signal-mapping.md shows it):
//
//   dimension            SI unit   accepted DBC units (scale to SI)
//   speed                m/s       m/s mps (1), km/h kph kmh km/hr (1/3.6), mph (0.44704),
//                                  kn knot knots (1852/3600)
//   acceleration         m/s^2     m/s^2 m/s2 m/s² mps2 m/s/s (1), g (9.80665),
//                                  cm/s^2 (0.01)
//   angular velocity     rad/s     rad/s (1), deg/s °/s dps deg/sec (pi/180), rpm (2 pi/60)
//   angle                rad       rad (1), mrad (0.001), deg ° degree degrees (pi/180)
//   pressure             Pa        Pa (1), hPa mbar (100), kPa (1000), bar (1e5), MPa (1e6),
//                                  psi (6894.757293168)
//   torque               N*m       Nm N*m N.m N-m (1), kNm (1000),
//                                  lbf*ft lb-ft lbft ft-lb (1.3558179483314)
//   length               m         m (1), cm (0.01), mm (0.001), um µm (1e-6),
//                                  in inch (0.0254)
//   dimensionless        1         "" - 1 (1)
//
// Each estimator input needs one dimension (input_dimension): wheel_torque torque,
// brake_pressure pressure, accel_x/accel_y acceleration, yaw_rate angular velocity, speed speed,
// steering_wheel_angle angle, rear_right_deflection length, gear dimensionless.
//
// Pure functions over a constant table; thread-safe.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/core/sample.hpp"

namespace vmass::signals {

enum class Dimension : std::uint8_t {
  kDimensionless,
  kSpeed,
  kAcceleration,
  kAngularVelocity,
  kAngle,
  kPressure,
  kTorque,
  kLength,
};

/// "speed", "acceleration", ...
std::string_view dimension_name(Dimension d);
/// The SI unit of a dimension as printed in messages ("m/s", "m/s^2", "rad/s", ...).
std::string_view si_unit(Dimension d);

struct UnitConversion {
  Dimension dimension = Dimension::kDimensionless;
  double scale = 1.0;  ///< SI value per DBC value
};

/// The conversion of a DBC unit string, or nothing when the unit is not in the table.
std::optional<UnitConversion> find_unit(std::string_view unit);

/// The dimension an estimator input needs.
Dimension input_dimension(Input input);

/// One row of the table, for documentation and error messages.
struct UnitRow {
  const char* unit;
  Dimension dimension;
  double scale;
};
/// Every accepted unit spelling, grouped by dimension.
const std::vector<UnitRow>& unit_table();
/// "km/h, m/s, mph, ..." : the accepted units of one dimension, for error messages.
std::string units_of(Dimension d);

}  // namespace vmass::signals
