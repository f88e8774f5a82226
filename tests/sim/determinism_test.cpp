// Same scenario + seed -> byte-identical outputs; the seed moves only the sensor noise.
#include <gtest/gtest.h>

#include <sstream>

#include "sim_test_util.hpp"
#include "vmass/sim/config_writer.hpp"
#include "vmass/sim/csv_writer.hpp"

namespace vmass::sim {
namespace {

struct Texts {
  std::string samples, truth, config;
};

Texts texts(const std::string& scenario, std::uint64_t seed, NoiseSet noise) {
  SimulationOptions o;
  o.seed = seed;
  o.noise = noise;
  const SimulationResult r = test::run(*find_scenario(scenario), o);
  std::ostringstream s, t, c;
  write_samples_csv(s, r.samples);
  write_truth_csv(t, r.truth);
  write_config_yaml(c, make_config_params(r.vehicle, r.initial_mass, r.tick_rate_hz), {});
  return {s.str(), t.str(), c.str()};
}

TEST(SimDeterminism, SameSeedGivesIdenticalBytes) {
  for (const std::string& name : scenario_names()) {
    const Texts a = texts(name, 42, NoiseSet::kEps3);
    const Texts b = texts(name, 42, NoiseSet::kEps3);
    EXPECT_EQ(a.samples, b.samples) << name;
    EXPECT_EQ(a.truth, b.truth) << name;
    EXPECT_EQ(a.config, b.config) << name;
    EXPECT_GT(a.samples.size(), 100000u) << name;
  }
}

TEST(SimDeterminism, AnotherSeedChangesTheNoiseButNotThePhysics) {
  SimulationOptions a;
  a.seed = 1;
  SimulationOptions b;
  b.seed = 2;
  const Scenario s = *find_scenario("paper_exp2");
  const SimulationResult ra = test::run(s, a);
  const SimulationResult rb = test::run(s, b);
  ASSERT_EQ(ra.samples.size(), rb.samples.size());
  int differing = 0;
  for (std::size_t k = 0; k < ra.samples.size(); ++k) {
    if (ra.samples[k].accel_x_mps2 != rb.samples[k].accel_x_mps2) ++differing;
    // The driver sees the true state, so the noise never feeds back into the motion.
    EXPECT_EQ(ra.truth[k].speed_mps, rb.truth[k].speed_mps);
    EXPECT_EQ(ra.truth[k].accel_y_mps2, rb.truth[k].accel_y_mps2);
    EXPECT_EQ(ra.truth[k].rear_right_deflection_m, rb.truth[k].rear_right_deflection_m);
  }
  EXPECT_GT(differing, 10000);
}

}  // namespace
}  // namespace vmass::sim
