// SignalTable: frames of the test DBC in, Samples out. Unit conversion, sums with gains, mux
// pages, staleness, NaN and out-of-range values, short frames, any id and length, counters,
// and no allocation per frame or tick.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <random>
#include <string>

#include "allocation_counter.hpp"
#include "test_dbc.hpp"
#include "vmass/core/constants.hpp"
#include "vmass/signals/signal_table.hpp"

namespace vmass::signals {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

const char* kInputs =
    "speed: {message: Speeds, signal: SpeedKmh}\n"
    "wheel_torque:\n"
    "  sum:\n"
    "    - {message: Torques, signal: Front}\n"
    "    - {message: Torques, signal: Rear, gain: 2.0}\n"
    "  offset: 5\n"
    "brake_pressure: {message: Torques, signal: Pressure}\n"
    "accel_x: {message: Imu, signal: AxG}\n"
    "yaw_rate: {message: Imu, signal: Yaw, gain: -1}\n"
    "steering_wheel_angle: {message: Imu, signal: Steer, timeout_s: 0.25}\n"
    "rear_right_deflection: {message: Level, signal: LevelRR, mux: 1}\n"
    "gear: {message: Level, signal: Gear, mux: 0}\n";

class SignalTableTest : public ::testing::Test {
 protected:
  SignalTableTest() : decoder_(testing::test_decoder()), table_(decoder_, mapping(kInputs)) {}

  /// The mapping, enforcing the DBC's [min|max] as can.enforce_dbc_ranges: true does (these
  /// tests check that option; the default is checked by DbcRangesAreNotValidityByDefault).
  SignalMapping mapping(const std::string& yaml) {
    SignalMapping m;
    const std::string e = parse_signal_mapping(YAML::Load(yaml), "t.yaml", *decoder_, "t", &m);
    EXPECT_EQ(e, "");
    m.enforce_dbc_ranges = true;
    return m;
  }
  can::CanFrame frame(const std::string& message, const std::map<std::string, double>& values,
                      TimeUs t_us) {
    return testing::make_frame(*decoder_, message, values, t_us);
  }
  void send(const std::string& message, const std::map<std::string, double>& values, TimeUs t_us) {
    EXPECT_EQ(table_.on_frame(frame(message, values, t_us)), can::DecodeStatus::kOk);
  }

  std::shared_ptr<const can::Decoder> decoder_;
  SignalTable table_;
};

TEST_F(SignalTableTest, NothingReceivedNothingValid) {
  const Sample s = table_.sample_at(1000);
  EXPECT_EQ(s.valid, 0u);
  EXPECT_EQ(s.time_us, 1000);
  EXPECT_EQ(table_.age_us(Input::kSpeed, 1000), -1);
  EXPECT_FALSE(table_.input_state(Input::kAccelY).mapped);
  EXPECT_TRUE(table_.input_state(Input::kSpeed).mapped);
  EXPECT_FALSE(table_.input_state(Input::kSpeed).received);
}

TEST_F(SignalTableTest, UnitsConvertToSi) {
  send("Speeds", {{"SpeedKmh", 90.0}}, 1000);
  send("Torques", {{"Front", 100.0}, {"Rear", 50.0}, {"Pressure", 2500.0}}, 1000);
  send("Imu", {{"AxG", 0.25}, {"Yaw", 12.5}, {"Steer", -45.0}}, 1000);
  send("Level", {{"Page", 1.0}, {"LevelRR", 23.45}}, 1000);
  send("Level", {{"Page", 0.0}, {"Gear", -1.0}}, 1000);
  const Sample s = table_.sample_at(2000);
  // All but a_y and the stand-ins this bus does not carry (brake switch, engine torque and speed).
  EXPECT_EQ(s.valid, kAllInputs & ~input_bit(Input::kAccelY) & ~input_bit(Input::kBrakeSwitch) &
                         ~input_bit(Input::kEngineTorque) & ~input_bit(Input::kEngineSpeed));
  EXPECT_NEAR(s.speed_mps, 25.0, 1e-12);                            // 90 km/h
  EXPECT_NEAR(s.wheel_torque_nm, 100.0 + 2.0 * 50.0 + 5.0, 1e-12);  // sum with gain + offset
  EXPECT_NEAR(s.brake_pressure_pa, 2.5e6, 1e-6);                    // 2500 kPa
  EXPECT_NEAR(s.accel_x_mps2, 0.25 * 9.80665, 1e-12);               // g
  EXPECT_NEAR(s.yaw_rate_radps, -12.5 * kPi / 180.0, 1e-12);        // deg/s, gain -1
  EXPECT_NEAR(s.steering_wheel_angle_rad, -45.0 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(s.rear_right_deflection_m, 0.02345, 1e-12);  // mm
  EXPECT_EQ(s.gear, -1);
  EXPECT_EQ(table_.age_us(Input::kSpeed, 2000), 1000);
  EXPECT_EQ(table_.age_us(Input::kSpeed, 500), 0);  // a frame after `now` is age 0
}

TEST_F(SignalTableTest, SumNeedsEveryTermAndAddsTheirLatestValues) {
  SignalTable t(decoder_, mapping("wheel_torque:\n  sum:\n"
                                  "    - {message: Torques, signal: Front}\n"
                                  "    - {message: Speeds, signal: NoUnit, gain: 10}\n"));
  t.on_frame(frame("Torques", {{"Front", 40.0}}, 0));
  EXPECT_FALSE(t.sample_at(0).has(Input::kWheelTorque));  // second term never received
  t.on_frame(frame("Speeds", {{"NoUnit", -3.0}}, 5000));
  Sample s = t.sample_at(5000);
  ASSERT_TRUE(s.has(Input::kWheelTorque));
  EXPECT_DOUBLE_EQ(s.wheel_torque_nm, 40.0 - 30.0);
  t.on_frame(frame("Torques", {{"Front", 41.5}}, 20000));
  s = t.sample_at(20000);
  EXPECT_DOUBLE_EQ(s.wheel_torque_nm, 41.5 - 30.0);
  // The age is the oldest term's; Speeds (10 ms cycle) times out after 50 ms.
  EXPECT_EQ(t.age_us(Input::kWheelTorque, 20000), 15000);
  EXPECT_TRUE(t.sample_at(55000).has(Input::kWheelTorque));
  EXPECT_FALSE(t.sample_at(55001).has(Input::kWheelTorque));
  EXPECT_EQ(t.counters().inputs[0].stale, 1u);
}

TEST_F(SignalTableTest, MuxPagesUpdateOnlyTheirSignals) {
  send("Level", {{"Page", 1.0}, {"LevelRR", 10.0}}, 0);
  send("Level", {{"Page", 0.0}, {"LevelFL", 99.0}, {"Gear", 3.0}}, 1000);
  Sample s = table_.sample_at(1000);
  EXPECT_NEAR(s.rear_right_deflection_m, 0.010, 1e-12);  // page 0 did not touch it
  EXPECT_EQ(s.gear, 3);
  send("Level", {{"Page", 2.0}}, 2000);  // a page nobody maps
  EXPECT_EQ(table_.input_state(Input::kRearRightDeflection).time_us, 0);
  EXPECT_EQ(table_.input_state(Input::kGear).time_us, 1000);
  EXPECT_EQ(table_.counters().inputs[static_cast<int>(Input::kRearRightDeflection)].updates, 1u);
}

TEST_F(SignalTableTest, ASignalOnTwoPagesIsTakenFromTheConfiguredPageOnly) {
  SignalTable t(decoder_, mapping("gear: {message: Level, signal: Shared, mux: 2}\n"));
  t.on_frame(frame("Level", {{"Page", 1.0}, {"Shared", 4.0}}, 0));
  EXPECT_FALSE(t.sample_at(0).has(Input::kGear));
  t.on_frame(frame("Level", {{"Page", 2.0}, {"Shared", 5.0}}, 1000));
  EXPECT_EQ(t.sample_at(1000).gear, 5);
  t.on_frame(frame("Level", {{"Page", 1.0}, {"Shared", 4.0}}, 2000));
  EXPECT_EQ(t.sample_at(2000).gear, 5);
  EXPECT_EQ(t.input_state(Input::kGear).time_us, 1000);
}

TEST_F(SignalTableTest, StaleAfterTheTimeoutAndBackWhenRefreshed) {
  // Speeds: 10 ms cycle -> 50 ms. Steer: timeout_s 0.25. Imu has no cycle time -> 0.1 s.
  send("Speeds", {{"SpeedKmh", 36.0}}, 100000);
  send("Imu", {{"AxG", 0.1}, {"Steer", 5.0}}, 100000);
  EXPECT_TRUE(table_.sample_at(150000).has(Input::kSpeed));
  EXPECT_FALSE(table_.sample_at(150001).has(Input::kSpeed));
  EXPECT_FALSE(table_.sample_at(160000).has(Input::kSpeed));
  EXPECT_EQ(table_.counters().inputs[static_cast<int>(Input::kSpeed)].stale, 1u);  // once
  EXPECT_TRUE(table_.sample_at(200000).has(Input::kAccelX));
  EXPECT_FALSE(table_.sample_at(200001).has(Input::kAccelX));
  EXPECT_TRUE(table_.sample_at(350000).has(Input::kSteeringWheelAngle));
  EXPECT_FALSE(table_.sample_at(350001).has(Input::kSteeringWheelAngle));
  send("Speeds", {{"SpeedKmh", 72.0}}, 400000);
  const Sample s = table_.sample_at(400000);
  ASSERT_TRUE(s.has(Input::kSpeed));
  EXPECT_NEAR(s.speed_mps, 20.0, 1e-12);
  EXPECT_FALSE(table_.sample_at(460000).has(Input::kSpeed));
  EXPECT_EQ(table_.counters().inputs[static_cast<int>(Input::kSpeed)].stale, 2u);
}

TEST_F(SignalTableTest, NanInfAndOutOfRangeAreInvalidForThatFrame) {
  const auto ax = static_cast<std::size_t>(Input::kAccelX);
  send("Imu", {{"AxG", kNan}, {"Yaw", 50.0}}, 0);
  Sample s = table_.sample_at(0);
  EXPECT_FALSE(s.has(Input::kAccelX));
  EXPECT_TRUE(s.has(Input::kYawRate));
  EXPECT_EQ(table_.counters().inputs[ax].invalid_values, 1u);
  send("Imu", {{"AxG", 0.5}, {"Yaw", 100.0}}, 1000);  // the range's edge is in range
  s = table_.sample_at(1000);
  EXPECT_TRUE(s.has(Input::kAccelX));
  EXPECT_NEAR(s.accel_x_mps2, 0.5 * 9.80665, 1e-12);
  EXPECT_TRUE(s.has(Input::kYawRate));
  send("Imu", {{"AxG", std::numeric_limits<double>::infinity()}, {"Yaw", 100.01}}, 2000);
  s = table_.sample_at(2000);
  EXPECT_FALSE(s.has(Input::kAccelX));
  EXPECT_FALSE(s.has(Input::kYawRate));                  // [-100|100] deg/s
  send("Imu", {{"AxG", -0.5}, {"Yaw", -327.68}}, 3000);  // absurd: raw -32768
  s = table_.sample_at(3000);
  EXPECT_TRUE(s.has(Input::kAccelX));
  EXPECT_FALSE(s.has(Input::kYawRate));
  EXPECT_EQ(table_.counters().inputs[ax].invalid_values, 2u);
  EXPECT_EQ(table_.counters().inputs[static_cast<int>(Input::kYawRate)].invalid_values, 2u);
  // The bad value is never applied: the last good one stays in the state.
  EXPECT_NEAR(table_.input_state(Input::kYawRate).value, -100.0 * kPi / 180.0, 1e-12);
  EXPECT_FALSE(table_.input_state(Input::kYawRate).good);
}

// Real files carry wrong ranges ([0|65535] on a signed yaw rate): by default a value outside
// the DBC's [min|max] is used as it is (the plausibility limits judge it, not the DBC).
TEST_F(SignalTableTest, DbcRangesAreNotValidityByDefault) {
  SignalMapping m;
  ASSERT_EQ(parse_signal_mapping(YAML::Load("yaw_rate: {message: Imu, signal: Yaw}"), "t.yaml",
                                 *decoder_, "t", &m),
            "");
  EXPECT_FALSE(m.enforce_dbc_ranges);
  SignalTable table(decoder_, m);
  table.on_frame(frame("Imu", {{"Yaw", -250.0}}, 0));  // the DBC says [-100|100] deg/s
  const Sample s = table.sample_at(0);
  ASSERT_TRUE(s.has(Input::kYawRate));
  EXPECT_NEAR(s.yaw_rate_radps, -250.0 * kPi / 180.0, 1e-12);
  EXPECT_EQ(table.counters().inputs[static_cast<int>(Input::kYawRate)].invalid_values, 0u);
}

TEST_F(SignalTableTest, ShortUnknownRemoteAndErrorFramesAreCounted) {
  send("Speeds", {{"SpeedKmh", 36.0}}, 0);
  can::CanFrame f = frame("Speeds", {{"SpeedKmh", 180.0}}, 1000);
  f.len = 7;  // shorter than the DBC's 8 bytes: rejected, never zero-filled
  EXPECT_EQ(table_.on_frame(f), can::DecodeStatus::kTooShort);
  EXPECT_NEAR(table_.sample_at(1000).speed_mps, 10.0, 1e-12);
  can::CanFrame unknown;
  unknown.id = 0x7FF;
  unknown.len = 8;
  EXPECT_EQ(table_.on_frame(unknown), can::DecodeStatus::kUnknownId);
  can::CanFrame same_id_extended = frame("Speeds", {{"SpeedKmh", 1.0}}, 0);
  same_id_extended.flags |= can::kExtended;  // 0x100 as a 29-bit id is another message
  EXPECT_EQ(table_.on_frame(same_id_extended), can::DecodeStatus::kUnknownId);
  can::CanFrame remote = frame("Speeds", {}, 0);
  remote.flags |= can::kRemote;
  EXPECT_EQ(table_.on_frame(remote), can::DecodeStatus::kRemote);
  can::CanFrame error;
  error.flags = can::kError;
  error.id = 0x40;
  EXPECT_EQ(table_.on_frame(error), can::DecodeStatus::kErrorFrame);
  const SignalTableCounters& c = table_.counters();
  EXPECT_EQ(c.frames, 6u);
  EXPECT_EQ(c.decoded, 1u);
  EXPECT_EQ(c.mapped, 1u);
  EXPECT_EQ(c.malformed, 1u);
  EXPECT_EQ(c.unknown_id, 2u);
  EXPECT_EQ(c.remote, 1u);
  EXPECT_EQ(c.error_frames, 1u);
  EXPECT_NEAR(table_.sample_at(2000).speed_mps, 10.0, 1e-12);
}

TEST_F(SignalTableTest, FramesOfAnyIdAndLengthNeverBreakIt) {
  std::mt19937_64 rng(20240607);
  std::uniform_int_distribution<int> byte(0, 255);
  const std::uint32_t known[] = {0x100, 0x101, 0x102, 0x200};
  TimeUs t = 0;
  for (int i = 0; i < 200000; ++i) {
    can::CanFrame f;
    const int kind = static_cast<int>(rng() % 4);
    if (kind == 0) {
      f.id = known[rng() % 4];
      if (f.id == 0x200) f.flags |= can::kExtended;
    } else if (kind == 1) {
      f.id = static_cast<std::uint32_t>(rng()) & can::kSffMask;
    } else {
      f.id = static_cast<std::uint32_t>(rng()) & can::kEffMask;
      f.flags |= can::kExtended;
    }
    f.flags |= static_cast<std::uint8_t>(rng() % 8 == 0 ? (rng() & 0x7E) : 0);
    f.len = static_cast<std::uint8_t>(rng() % 3 == 0 ? rng() % 256 : rng() % 9);
    for (std::uint8_t& b : f.data) b = static_cast<std::uint8_t>(byte(rng));
    t += static_cast<TimeUs>(rng() % 2000);
    table_.on_frame(f, t);
    const Sample s = table_.sample_at(t);
    for (int k = 0; k < kInputCount; ++k) {
      const auto in = static_cast<Input>(k);
      if (s.has(in)) {
        ASSERT_TRUE(std::isfinite(s.value(in))) << input_name(in);
      }
    }
    if (s.has(Input::kYawRate)) {
      ASSERT_LE(std::abs(s.yaw_rate_radps), 100.0 * kPi / 180 + 1e-9);
    }
    if (s.has(Input::kSpeed)) {
      ASSERT_LE(s.speed_mps, 300.0 / 3.6 + 1e-9);
    }
    if (s.has(Input::kGear)) {
      ASSERT_TRUE(s.gear >= -1 && s.gear <= 8) << s.gear;
    }
  }
  const SignalTableCounters& c = table_.counters();
  EXPECT_EQ(c.frames, 200000u);
  EXPECT_EQ(c.decoded + c.unknown_id + c.malformed + c.remote + c.error_frames, c.frames);
  EXPECT_GT(c.decoded, 10000u);
  EXPECT_GT(c.malformed, 1000u);
  EXPECT_GT(c.inputs[static_cast<int>(Input::kYawRate)].invalid_values, 100u);  // random bits
}

TEST_F(SignalTableTest, NoAllocationPerFrameOrTick) {
  if (!testing::counting_allocations())
    GTEST_SKIP() << "allocation counting is off under sanitizers";
  can::CanFrame frames[5] = {
      frame("Speeds", {{"SpeedKmh", 36.0}}, 0),
      frame("Torques", {{"Front", 1.0}, {"Rear", 2.0}}, 0),
      frame("Imu", {{"AxG", 0.1}, {"Yaw", 1.0}}, 0),
      frame("Level", {{"Page", 1.0}, {"LevelRR", 3.0}}, 0),
      frame("Level", {{"Page", 0.0}, {"Gear", 2.0}}, 0),
  };
  const long before = testing::allocations();
  double sum = 0.0;
  for (int i = 0; i < 10000; ++i) {
    table_.on_frame(frames[i % 5], i * 2000);
    const Sample s = table_.sample_at(i * 2000);
    sum += s.speed_mps + static_cast<double>(table_.age_us(Input::kGear, i * 2000));
  }
  EXPECT_EQ(testing::allocations() - before, 0);
  EXPECT_GT(sum, 0.0);
}

TEST_F(SignalTableTest, ResetForgetsValuesKeepsCounters) {
  send("Speeds", {{"SpeedKmh", 36.0}}, 0);
  table_.reset();
  EXPECT_FALSE(table_.sample_at(0).has(Input::kSpeed));
  EXPECT_EQ(table_.counters().frames, 1u);
}

}  // namespace
}  // namespace vmass::signals
