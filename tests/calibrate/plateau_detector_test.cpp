// Given a synthetic recording of a static ballast test (ramps while the ballast goes in, a slow
// settling creep after each, sensor noise and quantisation, someone leaning on the car, the car
// moved once), when the plateaus are detected, then there is one per load, each mean is the
// settled level (the creep rejected), and mismatches and bad series are reported.
#include "vmass/calibrate/plateau_detector.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "synthetic_ballast.hpp"
#include "vmass/calibrate/suspension_fit.hpp"

namespace vmass::calibrate {
namespace {

constexpr double kMm = 1e-3;

struct Recording {
  std::vector<DeflectionPoint> series;
  std::vector<double> levels_m;      ///< settled level of each hold
  std::vector<double> naive_mean_m;  ///< mean of each whole hold after its ramp (creep included)
};

// Holds of hold_s after ramps of 3 s; after each ramp the level creeps in as
// creep_m exp(-t / 1.5 s); noise 0.15 mm, 0.01 mm resolution, 100 Hz.
Recording record(const std::vector<double>& levels_m, double hold_s, double creep_m, unsigned seed,
                 bool disturbances) {
  Recording rec;
  rec.levels_m = levels_m;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.15 * kMm);
  const double dt = 0.01, ramp_s = 3.0, tau_s = 1.5;
  double t = 0.0;
  auto push = [&](double z, double speed) {
    DeflectionPoint p;
    p.time_s = t;
    p.deflection_m = std::round((z + noise(rng)) / (0.01 * kMm)) * 0.01 * kMm;
    p.speed_mps = speed;
    rec.series.push_back(p);
    t += dt;
  };
  for (std::size_t k = 0; k < levels_m.size(); ++k) {
    if (k > 0) {
      for (double u = 0.0; u < ramp_s; u += dt) {
        push(levels_m[k - 1] + (levels_m[k] - levels_m[k - 1]) * u / ramp_s, 0.0);
      }
    }
    double sum = 0.0;
    int n = 0;
    for (double u = 0.0; u < hold_s; u += dt) {
      double z = levels_m[k] + (k > 0 ? creep_m * std::exp(-u / tau_s) : 0.0);
      double speed = 0.0;
      if (disturbances && k == 4 && u > 9.0 && u < 10.0) z += 2.0 * kMm;  // someone leans on it
      if (disturbances && k == 6 && u > 8.0 && u < 10.0) {                // moved a little
        speed = 0.3;
        z += 0.8 * kMm * std::sin(6.0 * u);
      }
      sum += z;
      ++n;
      push(z, speed);
    }
    rec.naive_mean_m.push_back(sum / n);
  }
  return rec;
}

std::vector<double> ballast_levels() {
  std::vector<double> levels;
  for (int k = 0; k < 9; ++k) levels.push_back((12.0 + 7.26 * k) * kMm);
  return levels;
}

TEST(PlateauDetector, FindsOnePlateauPerLoadAndRejectsTheSettlingCreep) {
  const Recording rec = record(ballast_levels(), 20.0, 0.5 * kMm, 42, false);
  const PlateauDetection d = detect_plateaus(rec.series, PlateauParams{});
  ASSERT_TRUE(d.ok()) << d.error;
  ASSERT_EQ(d.plateaus.size(), 9u);
  EXPECT_NEAR(d.noise_std_m, 0.15 * kMm, 0.02 * kMm);
  for (std::size_t k = 0; k < 9; ++k) {
    const Plateau& p = d.plateaus[k];
    EXPECT_NEAR(p.deflection_m, rec.levels_m[k], 0.02 * kMm) << k;
    EXPECT_GT(p.sample_count, 1000) << k;
    if (k > 0) {
      // The naive hold average is biased by the creep; the detector's is not.
      EXPECT_GT(rec.naive_mean_m[k] - rec.levels_m[k], 0.03 * kMm);
    }
  }
}

TEST(PlateauDetector, DisturbancesSplitNothingAndTheMovedCarIsNotAPlateau) {
  const Recording rec = record(ballast_levels(), 25.0, 0.3 * kMm, 7, true);
  const PlateauDetection d = detect_plateaus(rec.series, PlateauParams{});
  ASSERT_TRUE(d.ok()) << d.error;
  ASSERT_EQ(d.plateaus.size(), 9u) << [&] {
    std::string s;
    for (const auto& n : d.notes) s += n + "\n";
    return s;
  }();
  for (std::size_t k = 0; k < 9; ++k) {
    EXPECT_NEAR(d.plateaus[k].deflection_m, rec.levels_m[k], 0.03 * kMm) << k;
  }
  bool merged = false;
  for (const std::string& n : d.notes) merged |= n.find("merged") != std::string::npos;
  EXPECT_TRUE(merged);
}

TEST(PlateauDetector, StepsFromPlateausFeedTheFit) {
  const LoadGeometry g = testing::paper_geometry();
  const SuspensionParams truth = testing::true_linear();
  std::vector<double> levels, masses;
  for (int k = 0; k < 6; ++k) {
    masses.push_back(100.0 * k);
    levels.push_back(testing::deflection_for_force(truth, g.wheel_force_n(masses.back())));
  }
  const Recording rec = record(levels, 20.0, 0.4 * kMm, 3, false);
  const PlateauDetection d = detect_plateaus(rec.series, PlateauParams{});
  ASSERT_TRUE(d.ok()) << d.error;
  std::vector<BallastStep> steps;
  ASSERT_EQ(steps_from_plateaus(d.plateaus, masses, &steps), "");
  ASSERT_EQ(steps.size(), 6u);
  EXPECT_EQ(steps[3].added_mass_kg, 300.0);
  EXPECT_LT(steps[3].start_s, steps[3].end_s);
  const SuspensionFitResult r = fit_suspension(steps, g);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_NEAR(r.calibration->linear.stiffness_n_per_m.value, 30000.0, 0.003 * 30000.0);
}

TEST(PlateauDetector, CountMismatchListsThePlateausFound) {
  const Recording rec = record(ballast_levels(), 20.0, 0.0, 1, false);
  const PlateauDetection d = detect_plateaus(rec.series, PlateauParams{});
  ASSERT_TRUE(d.ok());
  std::vector<BallastStep> steps;
  const std::string m = steps_from_plateaus(d.plateaus, {0, 100, 200}, &steps);
  EXPECT_NE(m.find("found 9 standstill plateaus but 3 ballast masses"), std::string::npos) << m;
  EXPECT_NE(m.find("9) "), std::string::npos) << m;
  EXPECT_NE(m.find(": 70.0"), std::string::npos) << m;  // the last level, mm
}

TEST(PlateauDetector, BadSeriesIsReported) {
  std::vector<DeflectionPoint> s(10);
  for (int i = 0; i < 10; ++i) s[static_cast<std::size_t>(i)].time_s = 0.01 * i;
  s[4].deflection_m = std::nan("");
  EXPECT_NE(detect_plateaus(s, PlateauParams{}).error.find("NaN"), std::string::npos);
  s[4].deflection_m = 0.0;
  s[6].time_s = s[5].time_s;
  EXPECT_NE(detect_plateaus(s, PlateauParams{}).error.find("does not increase"), std::string::npos);
  PlateauParams bad;
  bad.window_s = 0.0;
  EXPECT_NE(detect_plateaus(s, bad).error.find("plateau.window_s"), std::string::npos);
}

TEST(PlateauDetector, ANoiseOnlyRecordingIsOnePlateau) {
  const Recording rec = record({12.0 * kMm}, 30.0, 0.0, 9, false);
  const PlateauDetection d = detect_plateaus(rec.series, PlateauParams{});
  ASSERT_TRUE(d.ok());
  ASSERT_EQ(d.plateaus.size(), 1u);
  EXPECT_NEAR(d.plateaus[0].deflection_m, 12.0 * kMm, 0.02 * kMm);
}

}  // namespace
}  // namespace vmass::calibrate
