// The registry the accuracy suite calls: names, construction, unknown names, unusable cars.
#include "vmass/baselines/baseline_factory.hpp"

#include <gtest/gtest.h>

#include "exact_streams.hpp"

namespace vmass::baselines {
namespace {

using testing::exact_car;
using testing::exact_force_stream;

TEST(BaselineFactory, MakesEveryNamedBaselineUnderItsName) {
  const std::vector<std::string> names = baseline_names();
  ASSERT_EQ(names, (std::vector<std::string>{"paper", "paper_lp", "vahidi2005", "fathy2008"}));
  for (const std::string& name : names) {
    const auto baseline = make_baseline(name, exact_car(1500.0), 100.0);
    ASSERT_NE(baseline, nullptr) << name;
    EXPECT_EQ(baseline->name(), name);
    EXPECT_FALSE(baseline->estimate().has_mass) << name << ": an estimate before any data";
  }
}

TEST(BaselineFactory, UnknownNameGivesNull) {
  EXPECT_EQ(make_baseline("vmass", exact_car(1500.0), 100.0), nullptr);
  EXPECT_EQ(make_baseline("", exact_car(1500.0), 100.0), nullptr);
}

TEST(BaselineFactory, EveryBaselineEstimatesOnExactData) {
  // Exact for all four: the speed, a_x and the force agree (see exact_streams.hpp).
  const auto samples = testing::exact_speed_stream(exact_car(1500.0), 2000.0, 0.02, 60.0);
  for (const std::string& name : baseline_names()) {
    const auto baseline = make_baseline(name, exact_car(1500.0), 100.0);
    for (const auto& s : samples) baseline->step(s);
    const BaselineEstimate e = baseline->estimate();
    EXPECT_TRUE(e.has_mass) << name;
    EXPECT_GT(e.updates, 0) << name;
  }
}

TEST(BaselineFactory, AnUnusableCarOrTickRateNeverGivesAMass) {
  NominalVehicle no_radius = exact_car(1500.0);
  no_radius.wheel_radius_m = 0.0;
  EXPECT_FALSE(no_radius.validate().empty());
  const auto samples = exact_force_stream(exact_car(1500.0), 2000.0, 3000.0, 0.0, 30.0);
  for (const std::string& name : baseline_names()) {
    const auto bad_car = make_baseline(name, no_radius, 100.0);
    const auto bad_rate = make_baseline(name, exact_car(1500.0), 0.0);
    for (const auto& s : samples) {
      bad_car->step(s);
      bad_rate->step(s);
    }
    EXPECT_FALSE(bad_car->estimate().has_mass) << name;
    EXPECT_FALSE(bad_rate->estimate().has_mass) << name;
  }
}

}  // namespace
}  // namespace vmass::baselines
