// The sensor model applies exactly the documented noise sets, biases and resolutions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim_test_util.hpp"
#include "vmass/sim/sensor_model.hpp"

namespace vmass::sim {
namespace {

using test::mean;
using test::run;
using test::stddev;

struct ForceNoise {
  std::vector<double> eps_truth;   // eps as drawn (truth column)
  std::vector<double> eps_signal;  // (measured torque - true torque) / r
};

ForceNoise force_noise(NoiseSet n, std::uint64_t seed) {
  SimulationOptions o;
  o.seed = seed;
  o.noise = n;
  const SimulationResult r = run(*find_scenario("paper_exp2"), o);
  ForceNoise f;
  for (std::size_t k = 0; k < r.samples.size(); ++k) {
    f.eps_truth.push_back(r.truth[k].wheel_force_noise_n);
    f.eps_signal.push_back((r.samples[k].wheel_torque_nm - r.truth[k].wheel_torque_nm) / 0.31);
  }
  return f;
}

TEST(SimSensors, Eps2HasMean300NewtonAndStd60) {
  const ForceNoise f = force_noise(NoiseSet::kEps2, 3);
  ASSERT_EQ(f.eps_truth.size(), 20001u);
  // sigma / sqrt(n) = 0.42 N; quantisation of 0.5 N*m adds at most 0.81 N per value
  EXPECT_NEAR(mean(f.eps_truth), 300.0, 1.7);
  EXPECT_NEAR(stddev(f.eps_truth), 60.0, 1.5);
  EXPECT_NEAR(mean(f.eps_signal), 300.0, 1.7);
  EXPECT_NEAR(stddev(f.eps_signal), 60.0, 1.5);
  for (std::size_t k = 0; k < f.eps_truth.size(); ++k) {
    EXPECT_NEAR(f.eps_signal[k], f.eps_truth[k], 0.25 / 0.31 + 1e-9);
  }
}

TEST(SimSensors, Eps1IsZeroMeanAndEps3IsUniformOnZeroTo600) {
  const ForceNoise e1 = force_noise(NoiseSet::kEps1, 4);
  EXPECT_NEAR(mean(e1.eps_truth), 0.0, 1.7);
  EXPECT_NEAR(stddev(e1.eps_truth), 60.0, 1.5);
  const ForceNoise e3 = force_noise(NoiseSet::kEps3, 4);
  EXPECT_NEAR(mean(e3.eps_truth), 300.0, 5.0);  // sigma/sqrt(n) = 1.2 N
  EXPECT_NEAR(stddev(e3.eps_truth), 600.0 / std::sqrt(12.0), 3.0);
  EXPECT_GE(*std::min_element(e3.eps_truth.begin(), e3.eps_truth.end()), 0.0);
  EXPECT_LT(*std::max_element(e3.eps_truth.begin(), e3.eps_truth.end()), 600.0);
  const ForceNoise none = force_noise(NoiseSet::kNone, 4);
  for (double e : none.eps_truth) EXPECT_EQ(e, 0.0);
  for (double e : none.eps_signal) EXPECT_LE(std::abs(e), 0.25 / 0.31 + 1e-9);
}

TEST(SimSensors, ChannelsCarryTheDocumentedBiasNoiseAndResolution) {
  SimulationOptions o;
  o.seed = 9;
  const Scenario s = *find_scenario("paper_exp2");
  const SimulationResult r = run(s, o);
  const SensorSpec& spec = s.sensors;
  std::vector<double> ax, ay, yaw, sw, defl;
  for (std::size_t k = 0; k < r.samples.size(); ++k) {
    const Sample& m = r.samples[k];
    const TruthRow& t = r.truth[k];
    EXPECT_EQ(m.valid, kSensorModelInputs);
    ax.push_back(m.accel_x_mps2 - t.accel_x_mps2);
    ay.push_back(m.accel_y_mps2 - t.accel_y_mps2);
    yaw.push_back(m.yaw_rate_radps - t.yaw_rate_radps);
    sw.push_back(m.steering_wheel_angle_rad - t.steering_wheel_angle_rad);
    defl.push_back(m.rear_right_deflection_m - t.rear_right_deflection_m);
    EXPECT_NEAR(m.accel_x_mps2 / 0.01, std::round(m.accel_x_mps2 / 0.01), 1e-6);
    EXPECT_NEAR(m.rear_right_deflection_m / 1e-5, std::round(m.rear_right_deflection_m / 1e-5),
                1e-6);
    EXPECT_NEAR(m.wheel_torque_nm / 0.5, std::round(m.wheel_torque_nm / 0.5), 1e-9);
    EXPECT_EQ(m.gear, t.gear);
    if (t.speed_mps < 0.1) {
      EXPECT_EQ(m.speed_mps, 0.0);
    }
    EXPECT_GE(m.brake_pressure_pa, 0.0);
  }
  auto with_quant = [](double sd, double res) { return std::sqrt(sd * sd + res * res / 12.0); };
  EXPECT_NEAR(mean(ax), spec.accel_x_mps2.bias, 0.001);
  EXPECT_NEAR(stddev(ax), with_quant(0.02, 0.01), 0.001);
  EXPECT_NEAR(mean(ay), spec.accel_y_mps2.bias, 0.001);
  EXPECT_NEAR(mean(yaw), spec.yaw_rate_radps.bias, 5e-5);
  EXPECT_NEAR(stddev(yaw), with_quant(0.0015, spec.yaw_rate_radps.resolution), 1e-4);
  EXPECT_NEAR(mean(sw), spec.steering_wheel_angle_rad.bias, 1e-4);
  EXPECT_NEAR(mean(defl), 0.0002, 5e-6);
  EXPECT_NEAR(stddev(defl), with_quant(0.00015, 1e-5), 1e-5);
}

TEST(SimSensors, NoiseSetNamesRoundTrip) {
  for (NoiseSet n : {NoiseSet::kNone, NoiseSet::kEps1, NoiseSet::kEps2, NoiseSet::kEps3}) {
    EXPECT_EQ(parse_noise_set(noise_set_name(n)), n);
  }
  EXPECT_FALSE(parse_noise_set("eps4").has_value());
  EXPECT_FALSE(parse_noise_set("").has_value());
}

TEST(SimSensors, QuantiseRoundsToTheNearestStep) {
  EXPECT_DOUBLE_EQ(quantise(0.014, 0.01), 0.01);
  EXPECT_DOUBLE_EQ(quantise(-0.016, 0.01), -0.02);
  EXPECT_DOUBLE_EQ(quantise(1.2345, 0.0), 1.2345);
}

}  // namespace
}  // namespace vmass::sim
