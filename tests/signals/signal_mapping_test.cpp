// SignalMapping: the `can:` section resolved against a DBC; every config error names the file,
// the line and the key.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "test_dbc.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::signals {
namespace {

namespace fs = std::filesystem;

// Resolves `inputs` (YAML text of the can.inputs map, starting on line 1) against the test DBC.
std::string map_inputs(const std::string& yaml, SignalMapping* out = nullptr) {
  static const auto decoder = testing::test_decoder();
  SignalMapping mapping;
  const std::string error =
      parse_signal_mapping(YAML::Load(yaml), "test.yaml", *decoder, "test.dbc", &mapping);
  if (out) *out = mapping;
  return error;
}

void expect_error(const std::string& yaml, const std::string& expected) {
  const std::string error = map_inputs(yaml);
  EXPECT_NE(error.find(expected), std::string::npos)
      << "expected: " << expected << "\n     got: " << error << "\n    yaml: " << yaml;
}

TEST(SignalMapping, PlainSumAndMuxMappingsResolve) {
  SignalMapping m;
  ASSERT_EQ(map_inputs("speed: {message: Speeds, signal: SpeedKmh}\n"
                       "wheel_torque:\n"
                       "  sum:\n"
                       "    - {message: Torques, signal: Front}\n"
                       "    - {message: Torques, signal: Rear, gain: 2.0}\n"
                       "  offset: 5\n"
                       "brake_pressure: {message: Torques, signal: Pressure, timeout_s: 0.3}\n"
                       "rear_right_deflection: {message: Level, signal: LevelRR, mux: 1}\n"
                       "gear: {message: Level, signal: Gear, mux: 0}\n"
                       "accel_x: {message: Imu, signal: AxG, gain: -1}\n",
                       &m),
            "");
  ASSERT_EQ(m.inputs.size(), 6u);
  const InputMapping* speed = m.find(Input::kSpeed);
  ASSERT_NE(speed, nullptr);
  EXPECT_FALSE(speed->is_sum);
  EXPECT_NEAR(speed->terms[0].scale(), 1.0 / 3.6, 1e-15);
  EXPECT_DOUBLE_EQ(speed->terms[0].timeout_s, 0.05);  // 5 x 10 ms
  const InputMapping* torque = m.find(Input::kWheelTorque);
  ASSERT_NE(torque, nullptr);
  EXPECT_TRUE(torque->is_sum);
  ASSERT_EQ(torque->terms.size(), 2u);
  EXPECT_DOUBLE_EQ(torque->terms[1].scale(), 2.0);
  EXPECT_DOUBLE_EQ(torque->terms[0].timeout_s, 0.1);  // 5 x 20 ms
  EXPECT_DOUBLE_EQ(torque->offset, 5.0);
  EXPECT_DOUBLE_EQ(m.find(Input::kBrakePressure)->terms[0].scale(), 1000.0);
  EXPECT_DOUBLE_EQ(m.find(Input::kBrakePressure)->terms[0].timeout_s, 0.3);
  const MappedSignal& rr = m.find(Input::kRearRightDeflection)->terms[0];
  EXPECT_TRUE(rr.mux_switch.valid());
  EXPECT_EQ(rr.mux_value, 1u);
  EXPECT_DOUBLE_EQ(rr.timeout_s, 0.5);  // 5 x 100 ms
  EXPECT_DOUBLE_EQ(m.find(Input::kAccelX)->terms[0].scale(), -9.80665);
  EXPECT_DOUBLE_EQ(m.find(Input::kAccelX)->terms[0].timeout_s, 0.1);  // no cycle time
  EXPECT_EQ(m.find(Input::kYawRate), nullptr);
  EXPECT_NE(m.describe().find("speed <- Speeds.SpeedKmh"), std::string::npos) << m.describe();
}

TEST(SignalMapping, EmptyOrAbsentInputsMapNothing) {
  SignalMapping m;
  EXPECT_EQ(map_inputs("{}", &m), "");
  EXPECT_TRUE(m.inputs.empty());
  EXPECT_EQ(map_inputs("", &m), "");
  EXPECT_TRUE(m.inputs.empty());
}

TEST(SignalMapping, UnknownInputName) {
  expect_error("speed: {message: Speeds, signal: SpeedKmh}\nwhel_torque: {message: Torques}\n",
               "test.yaml:2: can.inputs.whel_torque: unknown input (known: wheel_torque,");
}

TEST(SignalMapping, MissingOrUnknownMessage) {
  expect_error("speed: {signal: SpeedKmh}\n", "test.yaml:1: can.inputs.speed.message: required");
  expect_error("speed: {message: Speedz, signal: SpeedKmh}\n",
               "test.yaml:1: can.inputs.speed.message: no message 'Speedz' in test.dbc");
  expect_error("speed: {message: speeds, signal: SpeedKmh}\n", "(did you mean 'Speeds'?)");
}

TEST(SignalMapping, MissingOrUnknownSignal) {
  expect_error("speed:\n  message: Speeds\n", "test.yaml:2: can.inputs.speed.signal: required");
  expect_error("speed:\n  message: Speeds\n  signal: Speed\n",
               "test.yaml:3: can.inputs.speed.signal: message 'Speeds' has no signal 'Speed'");
}

TEST(SignalMapping, MultiplexedSignalNeedsItsPage) {
  expect_error("rear_right_deflection: {message: Level, signal: LevelRR}\n",
               "test.yaml:1: can.inputs.rear_right_deflection.mux: signal 'Level.LevelRR' is "
               "multiplexed by 'Page' (pages 1): give the page to accept, e.g. mux: 1");
  expect_error("rear_right_deflection:\n  message: Level\n  signal: LevelRR\n  mux: 0\n",
               "test.yaml:4: can.inputs.rear_right_deflection.mux: Page = 0 does not select "
               "'Level.LevelRR' (pages 1)");
  expect_error("speed: {message: Speeds, signal: SpeedKmh, mux: 1}\n",
               "can.inputs.speed.mux: signal 'Speeds.SpeedKmh' is not multiplexed");
  expect_error("gear: {message: Level, signal: Gear, mux: -1}\n", "does not select");
}

TEST(SignalMapping, UnknownUnitNeedsAGain) {
  expect_error("speed: {message: Speeds, signal: Odd}\n",
               "test.yaml:1: can.inputs.speed.signal: Speeds.Odd has unit 'furlong/fortnight', "
               "which is not in the unit table: give gain: (m/s per DBC unit) or unit: (one of "
               "m/s, mps, km/h");
  expect_error("speed: {message: Speeds, signal: NoUnit}\n",
               "can.inputs.speed.signal: Speeds.NoUnit has no unit: give gain:");
  SignalMapping m;
  EXPECT_EQ(map_inputs("speed: {message: Speeds, signal: Odd, gain: 0.000166}\n", &m), "");
  EXPECT_DOUBLE_EQ(m.inputs[0].terms[0].scale(), 0.000166);
  EXPECT_EQ(map_inputs("speed: {message: Speeds, signal: NoUnit, unit: km/h}\n", &m), "");
  EXPECT_DOUBLE_EQ(m.inputs[0].terms[0].scale(), 1.0 / 3.6);
  expect_error("speed:\n  message: Speeds\n  signal: NoUnit\n  unit: parsec/h\n",
               "test.yaml:4: can.inputs.speed.unit: unit 'parsec/h', which is not in the unit");
}

TEST(SignalMapping, UnitOfTheWrongDimension) {
  expect_error("accel_x: {message: Speeds, signal: SpeedKmh}\n",
               "test.yaml:1: can.inputs.accel_x.signal: Speeds.SpeedKmh has unit 'km/h', a speed; "
               "accel_x needs an acceleration (m/s^2,");
  expect_error("gear: {message: Speeds, signal: SpeedKmh}\n", "gear needs a dimensionless number");
  expect_error("accel_x:\n  message: Speeds\n  signal: SpeedKmh\n  unit: bar\n",
               "test.yaml:4: can.inputs.accel_x.unit: unit 'bar', a pressure; accel_x needs");
  // A gain does not excuse a wrong dimension.
  expect_error("accel_x: {message: Speeds, signal: SpeedKmh, gain: 2}\n", "a speed; accel_x");
}

TEST(SignalMapping, BadNumbers) {
  expect_error("speed:\n  message: Speeds\n  signal: SpeedKmh\n  gain: 0\n",
               "test.yaml:4: can.inputs.speed.gain: must be a finite number other than 0");
  expect_error("speed: {message: Speeds, signal: SpeedKmh, gain: .inf}\n", "speed.gain: must be");
  expect_error("speed: {message: Speeds, signal: SpeedKmh, gain: fast}\n",
               "can.inputs.speed.gain: expected a number, got 'fast'");
  expect_error("speed:\n  message: Speeds\n  signal: SpeedKmh\n  timeout_s: -1\n",
               "test.yaml:4: can.inputs.speed.timeout_s: must be a finite number > 0");
  expect_error("speed: {message: Speeds, signal: SpeedKmh, timeout_s: 0}\n", "timeout_s: must");
  expect_error("speed: {message: Speeds, signal: SpeedKmh, offset: .inf}\n",
               "can.inputs.speed.offset: must be a finite number");
  expect_error("gear: {message: Level, signal: Gear, mux: 0.5}\n",
               "can.inputs.gear.mux: expected an integer");
}

TEST(SignalMapping, UnknownKeysAndShapes) {
  expect_error("speed:\n  message: Speeds\n  signal: SpeedKmh\n  sgnal: x\n",
               "test.yaml:4: can.inputs.speed.sgnal: unknown key");
  expect_error("speed: 3\n", "test.yaml:1: can.inputs.speed: expected a map of keys");
  expect_error("speed:\n", "test.yaml:1: can.inputs.speed: expected {message, signal}");
  expect_error("- speed\n", "can.inputs: expected a map of keys");
}

TEST(SignalMapping, SumErrors) {
  expect_error("wheel_torque:\n  sum: []\n",
               "test.yaml:2: can.inputs.wheel_torque.sum: expected a non-empty list");
  expect_error("wheel_torque:\n  sum: {message: Torques}\n", "wheel_torque.sum: expected a");
  expect_error(
      "wheel_torque:\n  message: Torques\n  sum:\n    - {message: Torques, signal: Front}\n",
      "test.yaml:2: can.inputs.wheel_torque.message: not allowed beside sum:");
  expect_error(
      "wheel_torque:\n  sum:\n    - {message: Torques, signal: Front}\n"
      "    - {message: Torques, signal: Middle}\n",
      "test.yaml:4: can.inputs.wheel_torque.sum[1].signal: message 'Torques' has no "
      "signal 'Middle'");
  expect_error("wheel_torque:\n  sum:\n    - {message: Torques, signal: Front, offset: 1}\n",
               "test.yaml:3: can.inputs.wheel_torque.sum[0].offset: unknown key");
  expect_error("wheel_torque:\n  sum:\n    - Front\n",
               "test.yaml:3: can.inputs.wheel_torque.sum: element 0 must be a map");
  expect_error("wheel_torque:\n  sum:\n    - {message: Torques, signal: Front}\n  gain: 2\n",
               "can.inputs.wheel_torque.gain: not allowed beside sum:");
}

// ---------------------------------------------------------------- load_can_inputs (files)

class CanInputsFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vmass_signals_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_ / "dbc");
    write("dbc/car.dbc", testing::kTestDbc);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  CanInputsLoad load(const std::string& can_section) {
    write("config.yaml", std::string(kVehicle) + can_section);
    const ConfigLoad c = load_config((dir_ / "config.yaml").string());
    EXPECT_TRUE(c.ok()) << c.error;
    if (!c.ok()) return {};
    return load_can_inputs(*c.config);
  }
  void expect_error(const std::string& can_section, const std::string& expected) {
    const CanInputsLoad r = load(can_section);
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.error.find(expected), std::string::npos)
        << "expected: " << expected << "\n     got: " << r.error;
  }

  static constexpr const char* kVehicle =
      "vehicle:\n"
      "  empty_mass_kg: 1500\n"
      "  wheelbase_m: 2.7\n"
      "  cg_to_front_axle_m: 1.2\n"
      "  wheel_radius_m: 0.31\n"
      "  brake_gain_n_per_pa: 0.0033\n"
      "  steering_ratio: 15.5\n"
      "  cornering_stiffness_front_n_per_rad: 150000\n"
      "  cornering_stiffness_rear_n_per_rad: 170000\n"
      "suspension:\n"
      "  stiffness_n_per_m: 30000\n";  // 11 lines
  fs::path dir_;
};

TEST_F(CanInputsFiles, DbcPathIsRelativeToTheConfig) {
  const CanInputsLoad r = load(
      "can:\n  dbc: dbc/car.dbc\n  inputs:\n"
      "    speed: {message: Speeds, signal: SpeedMph}\n");
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.inputs->dbc_path, (dir_ / "dbc/car.dbc").string());
  EXPECT_EQ(r.inputs->decoder->message_count(), 4);
  ASSERT_EQ(r.inputs->mapping.inputs.size(), 1u);
  EXPECT_DOUBLE_EQ(r.inputs->mapping.inputs[0].terms[0].scale(), 0.44704);
}

TEST_F(CanInputsFiles, ErrorsNameTheFileLineAndKey) {
  const std::string config = (dir_ / "config.yaml").string();
  expect_error("", config + ": can: required section is missing");
  expect_error("can:\n  inputs: {}\n", config + ":13: can.dbc: required key is missing");
  expect_error("can:\n  dbc: dbc/car.dbc\n  dbcc: x\n", config + ":14: can.dbcc: unknown key");
  expect_error("can:\n  dbc: nothere.dbc\n", config + ":13: can.dbc: ");
  expect_error("can:\n  dbc: nothere.dbc\n", "nothere.dbc");
  write("dbc/bad.dbc",
        "VERSION \"\"\nBO_ 1 M: 8 X\n SG_ S : 0|16@1+ (1,0) [0|0] \"\" X\n"
        " SG_ T 0|8@1+ (1,0) [0|0] \"\" X\n");
  expect_error("can:\n  dbc: dbc/bad.dbc\n", config + ":13: can.dbc: ");
  expect_error("can:\n  dbc: dbc/bad.dbc\n", "bad.dbc:4");
  expect_error("can:\n  dbc: dbc/car.dbc\n  inputs:\n    speed: {message: Nope, signal: X}\n",
               config + ":15: can.inputs.speed.message: no message 'Nope' in dbc/car.dbc");
}

// The longitudinal block's torque path (check_torque_path): engine torque without the ratios
// needs the engine speed and vehicle.derive_overall_ratio.
TEST_F(CanInputsFiles, EngineTorqueNeedsRatiosOrTheEngineSpeed) {
  const std::string config = (dir_ / "config.yaml").string();
  const std::string engine_torque = "    engine_torque: {message: Torques, signal: Front}\n";
  const std::string engine_speed =
      "    engine_speed: {message: Speeds, signal: NoUnit, gain: 0.1047}\n";
  const std::string can = "can:\n  dbc: dbc/car.dbc\n  inputs:\n";
  // Neither ratios nor the engine speed: located at the engine torque's key.
  expect_error(can + engine_torque, config + ":15: can.inputs.engine_torque: no wheel_torque");
  expect_error(can + engine_torque, "map engine_speed and set vehicle.derive_overall_ratio");
  // The engine speed mapped, the key not set: it says which key.
  expect_error(can + engine_torque + engine_speed,
               "set vehicle.derive_overall_ratio: true (the ratio from engine_speed)");
}

TEST_F(CanInputsFiles, DerivedRatioConfigWithoutRatiosOrGearIsValid) {
  const std::string config = (dir_ / "config.yaml").string();
  std::string vehicle = kVehicle;
  vehicle.insert(vehicle.find("suspension:"), "  derive_overall_ratio: true\n");  // line 12
  const std::string can = "can:\n  dbc: dbc/car.dbc\n  inputs:\n";
  const std::string engine_torque = "    engine_torque: {message: Torques, signal: Front}\n";
  write("config.yaml", vehicle + can + engine_torque +
                           "    engine_speed: {message: Speeds, signal: NoUnit, gain: 0.1047}\n");
  ConfigLoad c = load_config(config);
  ASSERT_TRUE(c.ok()) << c.error;
  EXPECT_TRUE(c.config->pipeline.vehicle.derive_overall_ratio);
  const CanInputsLoad r = load_can_inputs(*c.config);
  EXPECT_TRUE(r.ok()) << r.error;
  // The key without the engine speed mapped is the error, at the engine torque's line.
  write("config.yaml", vehicle + can + engine_torque);
  c = load_config(config);
  ASSERT_TRUE(c.ok()) << c.error;
  const CanInputsLoad missing = load_can_inputs(*c.config);
  EXPECT_FALSE(missing.ok());
  EXPECT_NE(missing.error.find(config + ":16: can.inputs.engine_torque: "
                                        "vehicle.derive_overall_ratio needs engine_speed mapped"),
            std::string::npos)
      << missing.error;
}

}  // namespace
}  // namespace vmass::signals

namespace vmass::signals {
namespace {

// Files from many hands: a mapping onto a signal with factor 0 (always its offset) or onto a
// message name the DBC uses twice (the config would take the first) is refused.
TEST(SignalMappingManyHands, FactorZeroAndAmbiguousMessageNames) {
  can::DbcParseResult r = can::parse_dbc(R"(BO_ 1 Speeds: 8 E
 SG_ Zero : 0|16@1+ (0,0) [0|0] "km/h" E
 SG_ Kmh : 16|16@1+ (0.01,0) [0|0] "km/h" E
BO_ 2 Speeds: 8 E
 SG_ Kmh : 0|16@1+ (0.01,0) [0|0] "km/h" E
)",
                                         "twice.dbc");
  ASSERT_TRUE(r.ok());
  const auto decoder = can::Decoder::compile(std::move(r.database));
  ASSERT_TRUE(decoder);
  SignalMapping m;
  EXPECT_EQ(parse_signal_mapping(YAML::Load("speed: {message: Speeds, signal: Kmh}"), "c.yaml",
                                 *decoder, "twice.dbc", &m),
            "c.yaml:1: can.inputs.speed.message: 'Speeds' names 2 messages in twice.dbc: rename "
            "them in the DBC");
}

TEST(SignalMappingManyHands, FactorZeroIsRefused) {
  can::DbcParseResult r =
      can::parse_dbc("BO_ 1 Speeds: 8 E\n SG_ Zero : 0|16@1+ (0,0) [0|0] \"km/h\" E\n", "zero.dbc");
  const auto decoder = can::Decoder::compile(std::move(r.database));
  ASSERT_TRUE(decoder);
  SignalMapping m;
  EXPECT_EQ(parse_signal_mapping(YAML::Load("speed: {message: Speeds, signal: Zero}"), "c.yaml",
                                 *decoder, "zero.dbc", &m),
            "c.yaml:1: can.inputs.speed.signal: Speeds.Zero has factor 0 in zero.dbc: its value "
            "is always its offset; fix the DBC");
}

TEST(SignalMappingManyHands, AHugeTimeoutIsRefused) {
  expect_error("speed: {message: Speeds, signal: SpeedKmh, timeout_s: 1e13}",
               "test.yaml:1: can.inputs.speed.timeout_s: 1e+13 is beyond any plausible value");
}

}  // namespace
}  // namespace vmass::signals
