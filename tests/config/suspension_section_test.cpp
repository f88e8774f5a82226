// The one writer of the `suspension:` section and the loader agree: what is written loads back
// as the same parameters (17 digits: exactly; infinities as .inf), with the comments given.
#include "vmass/config/suspension_section.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "vmass/config/config.hpp"

namespace vmass {
namespace {

const char* kVehicle = R"(vehicle:
  empty_mass_kg: 1500
  wheelbase_m: 2.7
  cg_to_front_axle_m: 1.2
  wheel_radius_m: 0.31
  brake_gain_n_per_pa: 0.0033
  steering_ratio: 15.5
  cornering_stiffness_front_n_per_rad: 150000
  cornering_stiffness_rear_n_per_rad: 170000
)";

TEST(SuspensionSection, WrittenSectionLoadsBackExactly) {
  SuspensionParams p;
  p.stiffness_n_per_m = 31234.567891234567;
  p.empty_deflection_m = 0.0110872444401;
  p.progressive_knee_m = 0.0412;
  p.progressive_rate_n_per_m2 = 2.0e6;
  p.linear_range_kg = 414.5372783;
  p.calibrated_range_kg = std::numeric_limits<double>::infinity();
  const std::string yaml = suspension_section_yaml(p, {{"stiffness_n_per_m", "std 5 N/m"}}, 17);
  EXPECT_NE(yaml.find("stiffness_n_per_m: 31234.567891234568  # std 5 N/m"), std::string::npos)
      << yaml;
  EXPECT_NE(yaml.find("calibrated_range_kg: .inf"), std::string::npos) << yaml;
  const ConfigLoad loaded = load_config_text(std::string(kVehicle) + yaml, "written.yaml");
  ASSERT_TRUE(loaded.ok()) << loaded.error;
  const SuspensionParams& q = loaded.config->pipeline.suspension;
  for (const Field<SuspensionParams>& field : kSuspensionFields) {
    EXPECT_TRUE(field_equal(field, q, p)) << field.key;
  }
}

TEST(SuspensionSection, TheLoaderRequiresWhatTheTableRequires) {
  const ConfigLoad loaded = load_config_text(std::string(kVehicle) + "suspension: {}\n", "s.yaml");
  ASSERT_FALSE(loaded.ok());
  EXPECT_NE(loaded.error.find("suspension.stiffness_n_per_m"), std::string::npos) << loaded.error;
}

}  // namespace
}  // namespace vmass
