// Units: the DBC unit strings we convert, checked against conversions written out here.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "vmass/core/constants.hpp"
#include "vmass/signals/units.hpp"

namespace vmass::signals {
namespace {

void expect_unit(const std::string& unit, Dimension d, double scale) {
  const auto c = find_unit(unit);
  ASSERT_TRUE(c.has_value()) << "'" << unit << "'";
  EXPECT_EQ(c->dimension, d) << unit;
  EXPECT_NEAR(c->scale, scale, 1e-12 * std::abs(scale)) << unit;
}

TEST(Units, SpeedsToMetresPerSecond) {
  expect_unit("m/s", Dimension::kSpeed, 1.0);
  expect_unit("km/h", Dimension::kSpeed, 1000.0 / 3600.0);
  expect_unit("kph", Dimension::kSpeed, 1000.0 / 3600.0);
  expect_unit("mph", Dimension::kSpeed, 1609.344 / 3600.0);
  expect_unit("knots", Dimension::kSpeed, 1852.0 / 3600.0);
}

TEST(Units, AccelerationsRatesAnglesPressuresTorquesLengths) {
  expect_unit("m/s^2", Dimension::kAcceleration, 1.0);
  expect_unit("m/s2", Dimension::kAcceleration, 1.0);
  expect_unit("g", Dimension::kAcceleration, 9.80665);
  expect_unit("deg/s", Dimension::kAngularVelocity, kPi / 180.0);
  expect_unit("rad/s", Dimension::kAngularVelocity, 1.0);
  expect_unit("rpm", Dimension::kAngularVelocity, 2.0 * kPi / 60.0);
  expect_unit("deg", Dimension::kAngle, kPi / 180.0);
  expect_unit("rad", Dimension::kAngle, 1.0);
  expect_unit("bar", Dimension::kPressure, 100000.0);
  expect_unit("kPa", Dimension::kPressure, 1000.0);
  expect_unit("hPa", Dimension::kPressure, 100.0);
  expect_unit("MPa", Dimension::kPressure, 1e6);
  expect_unit("Pa", Dimension::kPressure, 1.0);
  expect_unit("psi", Dimension::kPressure, 4.4482216152605 / (0.0254 * 0.0254));
  expect_unit("Nm", Dimension::kTorque, 1.0);
  expect_unit("N*m", Dimension::kTorque, 1.0);
  expect_unit("lb-ft", Dimension::kTorque, 4.4482216152605 * 0.3048);
  expect_unit("mm", Dimension::kLength, 0.001);
  expect_unit("cm", Dimension::kLength, 0.01);
  expect_unit("m", Dimension::kLength, 1.0);
  expect_unit("in", Dimension::kLength, 0.0254);
  expect_unit("", Dimension::kDimensionless, 1.0);
}

TEST(Units, SpellingsFromRealFiles) {
  expect_unit("KM/H", Dimension::kSpeed, 1.0 / 3.6);
  expect_unit("Km/h", Dimension::kSpeed, 1.0 / 3.6);
  expect_unit(" km / h ", Dimension::kSpeed, 1.0 / 3.6);
  expect_unit("KPa", Dimension::kPressure, 1000.0);
  expect_unit("NM", Dimension::kTorque, 1.0);
  expect_unit("\xC2\xB0", Dimension::kAngle, kPi / 180.0);  // UTF-8 degree sign
  expect_unit("\xB0", Dimension::kAngle, kPi / 180.0);      // cp1252 degree sign
  expect_unit("\xC2\xB0/s", Dimension::kAngularVelocity, kPi / 180.0);
  expect_unit("m/s\xC2\xB2", Dimension::kAcceleration, 1.0);  // UTF-8 superscript two
  expect_unit("\xC2\xB5m", Dimension::kLength, 1e-6);         // micro sign
}

TEST(Units, UnknownUnitsAreNotGuessed) {
  for (const char* u : {"furlong", "%", "V", "A", "degC", "km", "s", "m/s^3", "kg"}) {
    EXPECT_FALSE(find_unit(u).has_value()) << u;
  }
}

TEST(Units, TableIsConsistent) {
  std::set<std::string> seen;
  for (const UnitRow& row : unit_table()) {
    const auto c = find_unit(row.unit);
    ASSERT_TRUE(c.has_value()) << row.unit;
    // The first row with a spelling wins; a later row with the same spelling must agree.
    EXPECT_EQ(c->dimension, row.dimension) << row.unit;
    EXPECT_DOUBLE_EQ(c->scale, row.scale) << row.unit;
    EXPECT_GT(row.scale, 0.0);
  }
  EXPECT_NE(units_of(Dimension::kSpeed).find("km/h"), std::string::npos);
}

TEST(Units, EveryInputHasItsDimension) {
  EXPECT_EQ(input_dimension(Input::kWheelTorque), Dimension::kTorque);
  EXPECT_EQ(input_dimension(Input::kBrakePressure), Dimension::kPressure);
  EXPECT_EQ(input_dimension(Input::kAccelX), Dimension::kAcceleration);
  EXPECT_EQ(input_dimension(Input::kAccelY), Dimension::kAcceleration);
  EXPECT_EQ(input_dimension(Input::kYawRate), Dimension::kAngularVelocity);
  EXPECT_EQ(input_dimension(Input::kSpeed), Dimension::kSpeed);
  EXPECT_EQ(input_dimension(Input::kSteeringWheelAngle), Dimension::kAngle);
  EXPECT_EQ(input_dimension(Input::kRearRightDeflection), Dimension::kLength);
  EXPECT_EQ(input_dimension(Input::kGear), Dimension::kDimensionless);
}

}  // namespace
}  // namespace vmass::signals
