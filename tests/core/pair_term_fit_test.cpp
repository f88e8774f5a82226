// PairTermSums: the rotating masses' scale error told from the gears' pairs (and the converter
// map's from the pairs it multiplies), the mass shift they make, and the std they leave; one
// gear cannot tell the rotating masses' error, and then the fit is the datasheet's term of the
// interval unchanged.
#include "vmass/core/pair_term_fit.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace vmass {
namespace {

constexpr double kMass = 24000.0;
constexpr double kMu = 150.0;
constexpr double kNoise = 300.0;
constexpr double kPriorStd = 0.17;
constexpr PairTermPriors kPriors{kPriorStd, 0.0};

// A pair in a gear whose configured rotating mass is rotating_kg; the true one is (1 + c) times
// it, so y (the force with the configured term taken off) keeps c rotating_kg da.
RegressionPair pair_in_gear(double rotating_kg, double c, double da, double noise) {
  RegressionPair p;
  p.delta_accel_mps2 = da;
  p.rotating_n = rotating_kg * da;
  p.rotating_mass_kg = rotating_kg;
  p.y_n = kMass * da + kMu + c * p.rotating_n + noise;
  p.noise_std_n = kNoise;
  p.information = 0.3;
  return p;
}

// pairs_per_gear pairs in each gear, da uniform in +-0.6 m/s^2, the noise N(0, kNoise^2).
void add_gears(const std::vector<double>& gear_masses_kg, double c, int pairs_per_gear,
               unsigned seed, PairTermSums* sums) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, kNoise);
  std::uniform_real_distribution<double> uniform_da(-0.6, 0.6);
  for (const double m : gear_masses_kg) {
    for (int i = 0; i < pairs_per_gear; ++i) {
      const double da = uniform_da(rng);
      sums->add(pair_in_gear(m, c, da, noise(rng)), 0.0);
    }
  }
}

PairTermSums drive(const std::vector<double>& gear_masses_kg, double c, int pairs_per_gear,
                   unsigned seed) {
  PairTermSums sums;
  add_gears(gear_masses_kg, c, pairs_per_gear, seed, &sums);
  return sums;
}

// The two-parameter least-squares mass of the same pairs (what the regression reads).
double two_parameter_mass(const std::vector<double>& gear_masses_kg, double c) {
  double weighted_da_da = 0.0;
  double weighted_extra = 0.0;
  for (const double m : gear_masses_kg) {
    weighted_da_da += 1.0;
    weighted_extra += c * m;
  }
  return kMass + weighted_extra / weighted_da_da;
}

TEST(PairTermFit, GearsWithDifferentRotatingMassesTellTheScaleAndTakeItOffTheMass) {
  const std::vector<double> gears = {6500.0, 3800.0, 2200.0, 1300.0, 800.0, 500.0};
  const double c = 0.2;
  const PairTermSums sums = drive(gears, c, 3000, 7);
  const PairTermFit fit = sums.fit(kPriors);
  EXPECT_NEAR(fit.rotating_error, c, 0.03);
  EXPECT_LT(fit.rotating_error_std, 0.25 * kPriorStd);
  // The regression reads M + c S (about +590 kg here); the shift takes most of it off.
  const double read = two_parameter_mass(gears, c);
  EXPECT_GT(read - kMass, 500.0);
  EXPECT_NEAR(read + fit.mass_shift_kg, kMass, 100.0);
  // What is left unknown of c, in kg, is well below the datasheet's term.
  const double datasheet_kg = kPriorStd * (read - kMass) / c;
  EXPECT_LT(fit.mass_std_kg, 0.3 * datasheet_kg);
}

TEST(PairTermFit, OneGearCannotTellTheScaleAndLeavesTheDatasheetTerm) {
  const PairTermSums sums = drive({3000.0}, 0.2, 5000, 11);
  const PairTermFit fit = sums.fit(kPriors);
  EXPECT_NEAR(fit.rotating_error, 0.0, 0.01);
  EXPECT_NEAR(fit.mass_shift_kg, 0.0, 30.0);
  EXPECT_NEAR(fit.rotating_error_std, kPriorStd, 0.01 * kPriorStd);
  EXPECT_NEAR(fit.mass_std_kg, kPriorStd * 3000.0, 0.02 * kPriorStd * 3000.0);
}

TEST(PairTermFit, TooFewPairsOrExactTermsGiveNoShift) {
  PairTermSums sums;
  EXPECT_EQ(sums.fit(kPriors).mass_shift_kg, 0.0);
  sums.add(pair_in_gear(3000.0, 0.2, 0.4, 0.0), 0.0);
  EXPECT_EQ(sums.fit(kPriors).mass_shift_kg, 0.0);
  const PairTermSums many = drive({6000.0, 600.0}, 0.2, 500, 3);
  const PairTermFit none = many.fit(PairTermPriors{});
  EXPECT_EQ(none.mass_shift_kg, 0.0);
  EXPECT_EQ(none.mass_std_kg, 0.0);
}

TEST(PairTermFit, SinceIsThePairsAfterTheSnapshotAndBadPairsAreIgnored) {
  const PairTermSums sums = drive({5000.0}, -0.2, 800, 5);
  const PairTermSums snapshot = sums;
  const PairTermSums later = drive({5000.0, 700.0}, 0.25, 800, 9);
  PairTermSums both = sums;
  add_gears({5000.0, 700.0}, 0.25, 800, 9, &both);
  RegressionPair bad = pair_in_gear(700.0, 0.25, 0.3, 0.0);
  bad.y_n = std::nan("");
  both.add(bad, 0.0);
  RegressionPair lateral = pair_in_gear(700.0, 0.25, 0.3, 0.0);
  lateral.block = Block::kLateral;
  both.add(lateral, 0.0);
  const PairTermSums stretch = both.since(snapshot);
  EXPECT_EQ(stretch.pairs(), later.pairs());
  EXPECT_NEAR(stretch.fit(kPriors).rotating_error, later.fit(kPriors).rotating_error, 1e-6);
  EXPECT_NEAR(stretch.fit(kPriors).rotating_error, 0.25, 0.05);
}

TEST(PairTermFit, TheConverterMapsErrorIsToldFromThePairsItMultiplies) {
  // An automatic pulling away: its first gear's pairs carry the converter's multiplication,
  // which its map understates by 15 % (c_conv = -0.15); the upper gears' pairs are locked.
  std::mt19937 rng(21);
  std::normal_distribution<double> noise(0.0, kNoise);
  std::uniform_real_distribution<double> uniform_da(-0.6, 0.6);
  PairTermSums sums;
  for (const double m : {6000.0, 3000.0, 1500.0}) {
    for (int i = 0; i < 3000; ++i) {
      const double da = uniform_da(rng);
      RegressionPair p = pair_in_gear(m, 0.0, da, noise(rng));
      if (m == 6000.0) {
        p.converter_n = 0.8 * kMass * da;  // the multiplication's share of the force
        p.y_n -= 0.15 * p.converter_n;
      }
      sums.add(p, 0.0);
    }
  }
  const PairTermFit fit = sums.fit({kPriorStd, 0.2});
  EXPECT_NEAR(fit.converter_error, -0.15, 0.02);
  EXPECT_NEAR(fit.rotating_error, 0.0, 0.03);
  // A third of the pairs read 0.15 x 0.8 of the mass low: the regression, 960 kg low.
  EXPECT_NEAR(fit.mass_shift_kg, 0.15 * 0.8 * kMass / 3.0, 100.0);
  // Left out (an exact map), the converter's error is read as a rotating one.
  EXPECT_LT(sums.fit(kPriors).rotating_error, -0.1);
}

}  // namespace
}  // namespace vmass
