// The config loader: every error names the file, the line and the key; unknown keys are errors.
#include "vmass/config/config.hpp"

#include <gtest/gtest.h>

namespace vmass {
namespace {

const char* kMinimal = R"(vehicle:
  empty_mass_kg: 1500
  wheelbase_m: 2.7
  cg_to_front_axle_m: 1.2
  wheel_radius_m: 0.31
  brake_gain_n_per_pa: 0.0033
  steering_ratio: 15.5
  cornering_stiffness_front_n_per_rad: 150000
  cornering_stiffness_rear_n_per_rad: 170000
suspension:
  stiffness_n_per_m: 30000
)";

TEST(Config, MinimalFileGivesDefaults) {
  const ConfigLoad c = load_config_text(kMinimal, "mini.yaml");
  ASSERT_TRUE(c.ok()) << c.error;
  EXPECT_EQ(c.config->pipeline.vehicle.empty_mass_kg, 1500.0);
  EXPECT_EQ(c.config->pipeline.estimator.type, RegressorType::kBayes);
  EXPECT_EQ(c.config->pipeline.estimator.differencing.tick_rate_hz, 100.0);
  EXPECT_TRUE(std::isinf(c.config->pipeline.suspension.linear_range_kg));
}

TEST(Config, UnknownKeyNamesFileLineAndKey) {
  const std::string text =
      std::string(kMinimal) + "estimator:\n  rls:\n    forgeting_factor: 0.99\n";
  const ConfigLoad c = load_config_text(text, "typo.yaml");
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error, "typo.yaml:14: estimator.rls.forgeting_factor: unknown key");
}

TEST(Config, BadNumberNamesTheKey) {
  std::string text = kMinimal;
  text.replace(text.find("2.7"), 3, "2,7m");
  const ConfigLoad c = load_config_text(text, "bad.yaml");
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error, "bad.yaml:3: vehicle.wheelbase_m: expected a number, got '2,7m'");
}

TEST(Config, MissingRequiredKey) {
  std::string text = kMinimal;
  text.erase(text.find("  wheel_radius_m: 0.31\n"), 23);
  const ConfigLoad c = load_config_text(text, "missing.yaml");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error.find("missing.yaml:2: vehicle.wheel_radius_m: required key is missing"),
            std::string::npos)
      << c.error;
}

TEST(Config, OutOfRangeValueNamesKeyAndBound) {
  const std::string text =
      std::string(kMinimal) + "estimator:\n  rls:\n    forgetting_factor: 0.5\n";
  const ConfigLoad c = load_config_text(text, "range.yaml");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error.find("forgetting_factor"), std::string::npos) << c.error;
  EXPECT_NE(c.error.find("0.5"), std::string::npos) << c.error;
}

TEST(Config, BadEstimatorTypeAndBadYaml) {
  const ConfigLoad t =
      load_config_text(std::string(kMinimal) + "estimator:\n  type: kalman\n", "type.yaml");
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.error, "type.yaml:13: estimator.type: expected 'rls' or 'bayes', got 'kalman'");
  const ConfigLoad y = load_config_text("vehicle: [1, 2\n", "broken.yaml");
  ASSERT_FALSE(y.ok());
  EXPECT_EQ(y.error.rfind("broken.yaml:", 0), 0u) << y.error;
  const ConfigLoad f = load_config("/nonexistent/vmass.yaml");
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.error, "/nonexistent/vmass.yaml: cannot open the config: No such file or directory");
}

TEST(Config, DifferencingStepMustBeWholeTicks) {
  const ConfigLoad c = load_config_text(
      std::string(kMinimal) + "estimator:\n  differencing_dt_s: 0.015\n", "dt.yaml");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error.find("estimator.differencing_dt_s"), std::string::npos) << c.error;
}

TEST(Config, TheLoadMonitorHasItsOwnDifferencing) {
  const ConfigLoad ok = load_config_text(std::string(kMinimal) +
                                             "estimator:\n  load_change:\n"
                                             "    differencing_dt_s: 0.3\n"
                                             "    filter_cutoff_hz: 2.0\n",
                                         "monitor.yaml");
  ASSERT_TRUE(ok.ok()) << ok.error;
  const EstimatorParams& e = ok.config->pipeline.estimator;
  EXPECT_EQ(e.monitor_differencing().differencing_dt_s, 0.3);
  EXPECT_EQ(e.monitor_differencing().filter_cutoff_hz, 2.0);
  EXPECT_EQ(e.monitor_differencing().tick_rate_hz, e.differencing.tick_rate_hz);
  EXPECT_NE(e.differencing.differencing_dt_s, 0.3);  // the belief's own is untouched
  const ConfigLoad bad = load_config_text(
      std::string(kMinimal) + "estimator:\n  load_change:\n    differencing_dt_s: 0.015\n",
      "monitor_dt.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error.find("estimator.load_change.differencing_dt_s"), std::string::npos)
      << bad.error;
}

TEST(Config, TheLoadMonitorsBatchIsReadAndChecked) {
  const ConfigLoad ok = load_config_text(
      std::string(kMinimal) + "estimator:\n  load_change:\n    batch_size: 25\n", "batch.yaml");
  ASSERT_TRUE(ok.ok()) << ok.error;
  EXPECT_EQ(ok.config->pipeline.estimator.load_change.batch_size, 25);
  const ConfigLoad bad = load_config_text(
      std::string(kMinimal) + "estimator:\n  load_change:\n    batch_size: -3\n", "batch.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error.find("estimator.load_change.batch_size"), std::string::npos) << bad.error;
}

TEST(Config, TheLoadMonitorsChangePriorIsReadAndChecked) {
  const std::string section = "estimator:\n  load_change:\n    change_prior: ";
  const ConfigLoad ok = load_config_text(std::string(kMinimal) + section + "0.2\n", "prior.yaml");
  ASSERT_TRUE(ok.ok()) << ok.error;
  EXPECT_EQ(ok.config->pipeline.estimator.load_change.change_prior, 0.2);
  for (const char* bad_value : {"0.0", "1.0", "-0.5"}) {
    const ConfigLoad bad =
        load_config_text(std::string(kMinimal) + section + bad_value + "\n", "prior.yaml");
    ASSERT_FALSE(bad.ok()) << bad_value;
    EXPECT_NE(bad.error.find("estimator.load_change.change_prior"), std::string::npos) << bad.error;
  }
}

TEST(Config, TheProvisionalLagSpreadIsReadAndChecked) {
  const std::string section = "estimator:\n  longitudinal:\n    lag:\n      provisional_std_s: ";
  const ConfigLoad ok = load_config_text(std::string(kMinimal) + section + "0.05\n", "lag.yaml");
  ASSERT_TRUE(ok.ok()) << ok.error;
  EXPECT_EQ(ok.config->pipeline.estimator.longitudinal.lag.provisional_std_s, 0.05);
  const ConfigLoad bad = load_config_text(std::string(kMinimal) + section + "-0.01\n", "lag.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error.find("estimator.longitudinal.lag.provisional_std_s"), std::string::npos)
      << bad.error;
}

TEST(Config, TheRotatingTermsSourceIsReadAndChecked) {
  const std::string section = "estimator:\n  longitudinal:\n    rotating_accel_source: ";
  EXPECT_EQ(load_config_text(kMinimal, "default.yaml")
                .config->pipeline.estimator.longitudinal.rotating_accel_source,
            RotatingAccelSource::kAuto);
  const ConfigLoad ok =
      load_config_text(std::string(kMinimal) + section + "accelerometer\n", "rot.yaml");
  ASSERT_TRUE(ok.ok()) << ok.error;
  EXPECT_EQ(ok.config->pipeline.estimator.longitudinal.rotating_accel_source,
            RotatingAccelSource::kAccelerometer);
  const ConfigLoad bad = load_config_text(std::string(kMinimal) + section + "gps\n", "rot.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error.find("rotating_accel_source"), std::string::npos) << bad.error;
  EXPECT_NE(bad.error.find("'auto', 'wheel_speed' or 'accelerometer'"), std::string::npos)
      << bad.error;
}

TEST(Config, TheDrivelineModeIsReadAndChecked) {
  const std::string section = "estimator:\n  longitudinal:\n    driveline_mode:\n";
  const DrivelineModeParams defaults = load_config_text(kMinimal, "default.yaml")
                                           .config->pipeline.estimator.longitudinal.driveline_mode;
  EXPECT_TRUE(defaults.enabled);
  EXPECT_DOUBLE_EQ(defaults.min_evidence_s, 10.0);
  const ConfigLoad ok = load_config_text(
      std::string(kMinimal) + section + "      enabled: false\n      candidates: 12\n", "m.yaml");
  ASSERT_TRUE(ok.ok()) << ok.error;
  EXPECT_FALSE(ok.config->pipeline.estimator.longitudinal.driveline_mode.enabled);
  EXPECT_EQ(ok.config->pipeline.estimator.longitudinal.driveline_mode.candidates, 12);
  const ConfigLoad bad =
      load_config_text(std::string(kMinimal) + section + "      band_high_hz: 0.5\n", "m.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error.find("estimator.longitudinal.driveline_mode.band_high_hz"), std::string::npos)
      << bad.error;
}

// estimator.learning.KEY: `good` is read into `field`, `bad` is refused naming the key.
void expect_learning_key_read_and_checked(const std::string& key, double LearningParams::*field,
                                          double good, const std::string& bad) {
  const std::string section = "estimator:\n  learning:\n    " + key + ": ";
  const ConfigLoad ok =
      load_config_text(std::string(kMinimal) + section + std::to_string(good) + "\n", "l.yaml");
  ASSERT_TRUE(ok.ok()) << ok.error;
  EXPECT_DOUBLE_EQ(ok.config->pipeline.estimator.learning.*field, good);
  const ConfigLoad refused =
      load_config_text(std::string(kMinimal) + section + bad + "\n", "l.yaml");
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error.find("estimator.learning." + key), std::string::npos) << refused.error;
}

TEST(Config, TheTyreChangesWideningIsReadAndChecked) {
  EXPECT_DOUBLE_EQ(load_config_text(kMinimal, "default.yaml")
                       .config->pipeline.estimator.learning.tyre_change_std_fraction,
                   0.02);
  expect_learning_key_read_and_checked("tyre_change_std_fraction",
                                       &LearningParams::tyre_change_std_fraction, 0.03, "0");
}

TEST(Config, TheDrivesShareOfTheModelFloorIsReadAndChecked) {
  expect_learning_key_read_and_checked("drive_error_std_fraction",
                                       &LearningParams::drive_error_std_fraction, 0.004, "-0.1");
}

TEST(Config, RawSectionsAreKeptForTheirLayers) {
  const ConfigLoad c = load_config_text(
      std::string(kMinimal) + "lcm:\n  url: memq://\ncan:\n  dbc: car.dbc\n", "raw.yaml");
  ASSERT_TRUE(c.ok()) << c.error;
  EXPECT_EQ(c.config->lcm["url"].as<std::string>(), "memq://");
  EXPECT_EQ(c.config->can["dbc"].as<std::string>(), "car.dbc");
}

}  // namespace
}  // namespace vmass

namespace vmass {
namespace {

// Files from many hands (issue 11): what was accepted silently is refused with file:line:key.
TEST(ConfigManyHands, DuplicateKeysAreRefusedNotFirstWins) {
  const ConfigLoad top = load_config_text(std::string(kMinimal) + "vehicle:\n  x: 1\n", "d.yaml");
  EXPECT_EQ(top.error, "d.yaml:12: vehicle: duplicate key (first at line 1)");
  std::string text = kMinimal;
  text.insert(text.find("  wheelbase_m"), "  empty_mass_kg: 900\n");
  const ConfigLoad nested = load_config_text(text, "n.yaml");
  EXPECT_EQ(nested.error, "n.yaml:3: vehicle.empty_mass_kg: duplicate key (first at line 2)");
}

TEST(ConfigManyHands, NumbersBeyondTheirUnitAreRefused) {
  std::string text = kMinimal;
  text.replace(text.find("1500"), 4, "1e300");
  EXPECT_EQ(load_config_text(text, "m.yaml").error,
            "m.yaml:2: vehicle.empty_mass_kg: 1e+300 is beyond any plausible value (|x| <= 1e+07 "
            "kg)");
  const ConfigLoad t = load_config_text(
      std::string(kMinimal) + "estimator:\n  static_init:\n    settle_s: 1e13\n", "t.yaml");
  EXPECT_EQ(t.error,
            "t.yaml:14: estimator.static_init.settle_s: 1e+13 is beyond any plausible value (|x| "
            "<= 1e+06 s)");
  std::string gears = kMinimal;
  gears.insert(gears.find("suspension:"), "  rotating_mass_by_gear_kg: [10, 1e99]\n");
  const ConfigLoad g = load_config_text(gears, "g.yaml");
  EXPECT_NE(g.error.find("vehicle.rotating_mass_by_gear_kg: element 1: 1e+99 is beyond"),
            std::string::npos)
      << g.error;
}

TEST(ConfigManyHands, ValidationErrorsNameTheLineOfTheirKey) {
  std::string text = kMinimal;
  text.replace(text.find("0.31"), 4, "-0.31");
  text += "estimator:\n  rls:\n    forgetting_factor: 0.5\n";
  const ConfigLoad c = load_config_text(text, "v.yaml");
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error.substr(0, c.error.find('\n')),
            "v.yaml:5: vehicle.wheel_radius_m: must be > 0, got -0.31");
  EXPECT_NE(c.error.find("\nv.yaml:14: estimator.rls.forgetting_factor: must be in"),
            std::string::npos)
      << c.error;
}

TEST(ConfigManyHands, AConverterMapNeedsItsCouplingPoint) {
  std::string text = kMinimal;
  text.insert(text.find("suspension:"), "  torque_converter_stall_torque_ratio: 2.1\n");
  const ConfigLoad c = load_config_text(text, "c.yaml");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error.find("vehicle.torque_converter_coupling_speed_ratio: must be in (0.5, 1) "
                         "with torque_converter_stall_torque_ratio"),
            std::string::npos)
      << c.error;
  text.insert(text.find("suspension:"), "  torque_converter_coupling_speed_ratio: 0.86\n");
  EXPECT_TRUE(load_config_text(text, "c.yaml").ok());
}

TEST(ConfigManyHands, AMappedWheelTorqueIsTheTorqueWhateverRatiosAreGiven) {
  // An automatic's gearbox datasheet beside a wheel torque: the ratios tell a slipping
  // converter from the engine speed, and the torque stays the wheels'.
  std::string text = kMinimal;
  text.insert(text.find("suspension:"),
              "  gear_ratios: [3.5, 2.0, 1.4]\n  final_drive_ratio: 4.0\n");
  const ConfigLoad engine = load_config_text(text, "e.yaml");
  ASSERT_TRUE(engine.ok()) << engine.error;
  EXPECT_FALSE(engine.config->pipeline.vehicle.wheel_torque_input);
  text += "can:\n  dbc: car.dbc\n  inputs:\n    wheel_torque: PT.WheelTorque\n";
  const ConfigLoad wheels = load_config_text(text, "w.yaml");
  ASSERT_TRUE(wheels.ok()) << wheels.error;
  EXPECT_TRUE(wheels.config->pipeline.vehicle.wheel_torque_input);
}

TEST(ConfigManyHands, SpecialFilesAreRefusedWithTheirKind) {
  EXPECT_EQ(load_config("/dev/zero").error,
            "/dev/zero: cannot read the config: is a character device");
  EXPECT_EQ(load_config("/tmp").error, "/tmp: cannot read the config: is a directory");
}

}  // namespace
}  // namespace vmass
