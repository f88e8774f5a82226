#include "vmass/signals/units.hpp"
#include "vmass/core/constants.hpp"

#include <cmath>

namespace vmass::signals {
namespace {

constexpr double kDeg = kPi / 180.0;

// Display spellings; lookups compare normalise()d forms.
const std::vector<UnitRow> kTable = {
    {"m/s", Dimension::kSpeed, 1.0},
    {"mps", Dimension::kSpeed, 1.0},
    {"km/h", Dimension::kSpeed, 1.0 / 3.6},
    {"kph", Dimension::kSpeed, 1.0 / 3.6},
    {"kmh", Dimension::kSpeed, 1.0 / 3.6},
    {"km/hr", Dimension::kSpeed, 1.0 / 3.6},
    {"mph", Dimension::kSpeed, 0.44704},
    {"kn", Dimension::kSpeed, 1852.0 / 3600.0},
    {"knot", Dimension::kSpeed, 1852.0 / 3600.0},
    {"knots", Dimension::kSpeed, 1852.0 / 3600.0},

    {"m/s^2", Dimension::kAcceleration, 1.0},
    {"m/s2", Dimension::kAcceleration, 1.0},
    {"m/s**2", Dimension::kAcceleration, 1.0},
    {"m/s/s", Dimension::kAcceleration, 1.0},
    {"mps2", Dimension::kAcceleration, 1.0},
    {"g", Dimension::kAcceleration, 9.80665},
    {"cm/s^2", Dimension::kAcceleration, 0.01},
    {"cm/s2", Dimension::kAcceleration, 0.01},

    {"rad/s", Dimension::kAngularVelocity, 1.0},
    {"rad/sec", Dimension::kAngularVelocity, 1.0},
    {"deg/s", Dimension::kAngularVelocity, kDeg},
    {"deg/sec", Dimension::kAngularVelocity, kDeg},
    {"dps", Dimension::kAngularVelocity, kDeg},
    {"rpm", Dimension::kAngularVelocity, 2.0 * kPi / 60.0},

    {"rad", Dimension::kAngle, 1.0},
    {"mrad", Dimension::kAngle, 1e-3},
    {"deg", Dimension::kAngle, kDeg},
    {"degree", Dimension::kAngle, kDeg},
    {"degrees", Dimension::kAngle, kDeg},

    {"Pa", Dimension::kPressure, 1.0},
    {"hPa", Dimension::kPressure, 100.0},
    {"mbar", Dimension::kPressure, 100.0},
    {"kPa", Dimension::kPressure, 1000.0},
    {"bar", Dimension::kPressure, 1e5},
    {"MPa", Dimension::kPressure, 1e6},
    {"psi", Dimension::kPressure, 6894.757293168},

    {"Nm", Dimension::kTorque, 1.0},
    {"N*m", Dimension::kTorque, 1.0},
    {"N.m", Dimension::kTorque, 1.0},
    {"N-m", Dimension::kTorque, 1.0},
    {"kNm", Dimension::kTorque, 1000.0},
    {"lbf*ft", Dimension::kTorque, 1.3558179483314004},
    {"lb-ft", Dimension::kTorque, 1.3558179483314004},
    {"lbft", Dimension::kTorque, 1.3558179483314004},
    {"ft-lb", Dimension::kTorque, 1.3558179483314004},

    {"m", Dimension::kLength, 1.0},
    {"cm", Dimension::kLength, 0.01},
    {"mm", Dimension::kLength, 1e-3},
    {"um", Dimension::kLength, 1e-6},
    {"in", Dimension::kLength, 0.0254},
    {"inch", Dimension::kLength, 0.0254},

    {"", Dimension::kDimensionless, 1.0},
    {"-", Dimension::kDimensionless, 1.0},
    {"1", Dimension::kDimensionless, 1.0},
};

// Lower case, spaces dropped, degree sign -> "deg", micro sign -> "u", superscript 2 -> "^2"
// (UTF-8 and cp1252 spellings of each).
std::string normalise(std::string_view unit) {
  std::string out;
  out.reserve(unit.size() + 4);
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const auto c = static_cast<unsigned char>(unit[i]);
    unsigned char symbol = c;
    if (c == 0xC2 && i + 1 < unit.size()) {  // UTF-8 two-byte sequences of Latin-1 symbols
      const auto next = static_cast<unsigned char>(unit[i + 1]);
      if (next == 0xB0 || next == 0xB5 || next == 0xB2) {
        symbol = next;
        ++i;
      }
    }
    if (symbol == 0xB0) {
      out += "deg";
    } else if (symbol == 0xB5) {
      out += "u";
    } else if (symbol == 0xB2) {
      out += "^2";
    } else if (symbol == ' ' || symbol == '\t') {
      continue;
    } else if (symbol >= 'A' && symbol <= 'Z') {
      out += static_cast<char>(symbol - 'A' + 'a');
    } else {
      out += static_cast<char>(symbol);
    }
  }
  return out;
}

}  // namespace

std::string_view dimension_name(Dimension d) {
  switch (d) {
    case Dimension::kDimensionless:
      return "dimensionless number";
    case Dimension::kSpeed:
      return "speed";
    case Dimension::kAcceleration:
      return "acceleration";
    case Dimension::kAngularVelocity:
      return "angular velocity";
    case Dimension::kAngle:
      return "angle";
    case Dimension::kPressure:
      return "pressure";
    case Dimension::kTorque:
      return "torque";
    case Dimension::kLength:
      return "length";
  }
  return "unknown";
}

std::string_view si_unit(Dimension d) {
  switch (d) {
    case Dimension::kDimensionless:
      return "1";
    case Dimension::kSpeed:
      return "m/s";
    case Dimension::kAcceleration:
      return "m/s^2";
    case Dimension::kAngularVelocity:
      return "rad/s";
    case Dimension::kAngle:
      return "rad";
    case Dimension::kPressure:
      return "Pa";
    case Dimension::kTorque:
      return "N*m";
    case Dimension::kLength:
      return "m";
  }
  return "?";
}

std::optional<UnitConversion> find_unit(std::string_view unit) {
  const std::string key = normalise(unit);
  for (const UnitRow& row : kTable) {
    if (key == normalise(row.unit)) return UnitConversion{row.dimension, row.scale};
  }
  return std::nullopt;
}

Dimension input_dimension(Input input) {
  switch (input) {
    case Input::kWheelTorque:
      return Dimension::kTorque;
    case Input::kBrakePressure:
      return Dimension::kPressure;
    case Input::kAccelX:
    case Input::kAccelY:
      return Dimension::kAcceleration;
    case Input::kYawRate:
      return Dimension::kAngularVelocity;
    case Input::kSpeed:
      return Dimension::kSpeed;
    case Input::kSteeringWheelAngle:
      return Dimension::kAngle;
    case Input::kRearRightDeflection:
      return Dimension::kLength;
    case Input::kEngineTorque:
      return Dimension::kTorque;
    case Input::kEngineSpeed:
      return Dimension::kAngularVelocity;
    case Input::kGear:
    case Input::kBrakeSwitch:
    case Input::kCount:
      break;
  }
  return Dimension::kDimensionless;
}

const std::vector<UnitRow>& unit_table() { return kTable; }

std::string units_of(Dimension d) {
  std::string s;
  for (const UnitRow& row : kTable) {
    if (row.dimension != d) continue;
    if (!s.empty()) s += ", ";
    s += row.unit[0] == '\0' ? "\"\"" : row.unit;
  }
  return s;
}

}  // namespace vmass::signals
