// What vmass learns about each gear's rotating mass across drives (LearntGearMasses), alone and
// through the pipeline's drives.
#include "vmass/core/learnt_gear_masses.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "learning_car.hpp"
#include "synthetic_drive.hpp"
#include "vmass/core/pipeline.hpp"

namespace vmass {
namespace {

// A truck-like box: the config's rotating mass per gear, kg.
const std::vector<double> kConfigKg = {6000.0, 3000.0, 1200.0, 600.0};

LearntGearMasses truck_gears() { return LearntGearMasses(kConfigKg, 0.3, 0.01, 20); }

/// A drive's sums as its pairs would give them: each listed gear reads mass + delta (its
/// effective mass), with `precision` (1/kg^2) of pairs behind it.
GearPairSums drive_reading(double mass_kg, const std::vector<double>& delta_kg,
                           const std::vector<int>& gears, double precision = 1e-3) {
  GearPairSums s;
  for (int g : gears) {
    const auto i = static_cast<std::size_t>(g - 1);
    s.da_da[i] = precision;
    s.da_y[i] = precision * (mass_kg + delta_kg[i]);
    s.da_wheel[i] = precision;
    s.pairs[i] = 200;
    s.all_da_da += precision;
  }
  return s;
}

TEST(LearntGearMassesTest, StartsAtTheDatasheetAndOneGearTellsNothing) {
  LearntGearMasses g = truck_gears();
  EXPECT_EQ(g.gears(), 4);
  EXPECT_FALSE(g.learnt());
  // The datasheet's belief is one a state file may hold (a drive that taught nothing saves it).
  EXPECT_EQ(g.implausible(g.state()), "");
  const LearntGearMasses saloon({659.910899, 312.715006, 168.050051, 122.950751, 91.6586083,
                                 73.1832243, 64.9929622, 57.851521},
                                0.3, 0.01, 20);
  EXPECT_EQ(saloon.implausible(saloon.state()), "");
  EXPECT_EQ(g.correction_kg(1), 0.0);
  EXPECT_EQ(g.correction_kg(5), 0.0);  // beyond the config's gears
  // The datasheet's +-30 % (uniform) in two equal parts: the gear's own and the common one.
  EXPECT_NEAR(g.correction_std_kg(1), std::sqrt(2.0) * 0.3 / std::sqrt(3.0) * 6000.0, 1e-6);
  // A drive in one gear cannot tell its gear from the mass.
  const std::vector<double> delta = {-2000.0, -600.0, -100.0, 0.0};
  EXPECT_FALSE(g.add_evidence(drive_reading(20000.0, delta, {2}), 20000.0, 0.0));
  EXPECT_FALSE(g.learnt());
  // Nor do gears with too few pairs.
  GearPairSums few = drive_reading(20000.0, delta, {1, 4});
  few.pairs[0] = 5;
  EXPECT_FALSE(g.add_evidence(few, 20000.0, 0.0));
}

TEST(LearntGearMassesTest, LearnsHowTheGearsDifferFromDrivesOfManyLoads) {
  LearntGearMasses g = truck_gears();
  // The truth: the low gears carry less than the config says. Drives on different loads and
  // gear mixes (urban in 1-3, highway in 3-4, a launch through all).
  const std::vector<double> delta = {-2000.0, -600.0, -100.0, 0.0};
  const std::vector<std::vector<int>> mixes = {{1, 2, 3}, {3, 4}, {1, 2, 3, 4}, {2, 3, 4}};
  for (int d = 0; d < 12; ++d) {
    const double mass = 15000.0 + 2500.0 * (d % 5);
    ASSERT_TRUE(g.add_evidence(drive_reading(mass, delta, mixes[d % 4]), mass, 0.0));
  }
  EXPECT_EQ(g.state().drives, 12);
  // What the gears tell is their differences; the top gear's small config mass pins the level.
  for (int gear = 1; gear <= 3; ++gear) {
    const double learnt_difference = g.correction_kg(gear) - g.correction_kg(4);
    const double true_difference = delta[std::size_t(gear - 1)] - delta[3];
    EXPECT_NEAR(learnt_difference, true_difference, 0.05 * std::abs(delta[0])) << gear;
  }
  EXPECT_NEAR(g.correction_kg(4), 0.0, 150.0);
  EXPECT_LT(g.correction_std_kg(1), 0.3 * truck_gears().correction_std_kg(1));
  // A drive in gear 1 alone now rests on what was learnt: its variance is the belief's.
  const GearPairSums urban = drive_reading(20000.0, delta, {1});
  EXPECT_NEAR(g.mass_variance_kg2(urban, 20000.0), std::pow(g.correction_std_kg(1), 2), 1e-6);
  EXPECT_LT(g.mass_variance_kg2(urban, 20000.0), truck_gears().mass_variance_kg2(urban, 20000.0));
}

TEST(LearntGearMassesTest, AnInterceptOfTheDriveIsTakenOutOfEachGearsReading) {
  LearntGearMasses with_mu = truck_gears();
  LearntGearMasses without = truck_gears();
  const std::vector<double> delta = {-1500.0, -300.0, 0.0, 0.0};
  GearPairSums s = drive_reading(20000.0, delta, {1, 2, 4});
  // Every pair carries mu = 400 N: y = (M + delta) da + mu.
  for (std::size_t i = 0; i < 4; ++i) {
    s.da[i] = 0.3 * s.da_da[i];
    s.da_y[i] += 400.0 * s.da[i];
  }
  ASSERT_TRUE(with_mu.add_evidence(s, 20000.0, 400.0));
  ASSERT_TRUE(without.add_evidence(drive_reading(20000.0, delta, {1, 2, 4}), 20000.0, 0.0));
  for (int gear = 1; gear <= 4; ++gear) {
    EXPECT_NEAR(with_mu.correction_kg(gear), without.correction_kg(gear), 1e-6) << gear;
  }
}

TEST(LearntGearMassesTest, RefusesWhatNoInertiaErrorExplainsAndRestoresOnlyWhatItCouldHold) {
  LearntGearMasses g = truck_gears();
  // Gear 1 reading 9 t less than gear 4 on every drive: more than its whole configured mass.
  const std::vector<double> absurd = {-9000.0, 0.0, 0.0, 0.0};
  int taken = 0;
  for (int d = 0; d < 10; ++d) {
    taken += g.add_evidence(drive_reading(20000.0, absurd, {1, 4}, 1e-2), 20000.0, 0.0) ? 1 : 0;
  }
  EXPECT_EQ(taken, 0);
  EXPECT_FALSE(g.learnt());
  const std::vector<double> delta = {-1000.0, -300.0, 0.0, 0.0};
  ASSERT_TRUE(g.add_evidence(drive_reading(20000.0, delta, {1, 2, 4}), 20000.0, 0.0));

  LearntGearMasses other = truck_gears();
  GearMassesState bad = g.state();
  bad.gears = 3;
  EXPECT_NE(other.implausible(bad), "");
  EXPECT_FALSE(other.restore(bad));
  bad = g.state();
  bad.covariance_kg2[1] += 1.0;  // not symmetric
  EXPECT_NE(other.implausible(bad), "");
  bad = g.state();
  bad.correction_kg[1] = 3500.0;  // beyond gear 2's 3000 kg
  EXPECT_NE(other.implausible(bad), "");
  bad = g.state();
  bad.covariance_kg2[0] = -1.0;
  EXPECT_NE(other.implausible(bad), "");
  EXPECT_TRUE(other.restore(g.state()));
  EXPECT_EQ(other.correction_kg(1), g.correction_kg(1));
  other.reset();
  EXPECT_FALSE(other.learnt());
  EXPECT_EQ(other.correction_kg(1), 0.0);
}

/// The mass a drive on `mass_kg` in `mix` reads through the pipeline's arithmetic: its pairs
/// (of a car whose true scale is 1 and true corrections `delta`) divided by `scale`, the
/// corrections `applied` subtracted.
double reading_kg(double mass_kg, const std::vector<double>& delta, const GearPairSums& mix,
                  double scale, const LearntGearMasses& applied) {
  double level = 0.0;
  double applied_level = 0.0;
  for (int gear = 1; gear <= 4; ++gear) {
    const double share = mix.da_wheel[std::size_t(gear - 1)] / mix.all_da_da;
    level += share * delta[std::size_t(gear - 1)];
    applied_level += share * applied.correction_kg(gear);
  }
  return (mass_kg + level) / scale - applied_level;
}

// A known mass taught the lumped scale on a drive in some gear mix, with the corrections of that
// time: the scale holds that mix's level relative to the drive's mass. The scale factor takes
// it off, so that the corrections, applied whole in kg, are right at any mass: a truck's known
// mass at 12 t does not leave e (1/M2 - 1/M1) at 27 t.
TEST(LearntGearMassesTest, TheKnownMassDrivesLevelLeavesTheScaleRelativeToItsMass) {
  const std::vector<double> delta = {-2000.0, -600.0, -100.0, 0.0};
  const LearntGearMasses datasheet = truck_gears();
  EXPECT_EQ(datasheet.scale_factor(), 1.0);  // no reference yet
  const GearPairSums urban = drive_reading(12000.0, delta, {1, 2});
  // The known-mass drive: urban at 12 t, nothing applied yet. Its evidence, far better than
  // the datasheet, is what the lumped scale learnt.
  const double m1 = 12000.0;
  const double learnt_scale = reading_kg(m1, delta, urban, 1.0, datasheet) / m1;
  // Later, the gears' belief holds the truth.
  GearMassesState truth = datasheet.state();
  for (std::size_t i = 0; i < 4; ++i) truth.correction_kg[i] = delta[i];
  LearntGearMasses g = truck_gears();
  ASSERT_TRUE(g.restore(truth));
  g.add_reference(urban, m1, 1e-10, 1e-2, datasheet);
  EXPECT_NEAR(g.scale_factor() * learnt_scale, 1.0, 1e-6);
  for (double m2 : {12000.0, 27000.0, 40000.0}) {
    EXPECT_NEAR(reading_kg(m2, delta, urban, learnt_scale * g.scale_factor(), g), m2, 1e-3) << m2;
  }
  // Evidence as good as the datasheet: the scale holds half of the level.
  LearntGearMasses even = truck_gears();
  ASSERT_TRUE(even.restore(truth));
  even.add_reference(urban, m1, 1e-4, 1e-4, datasheet);
  EXPECT_NEAR(1.0 / even.scale_factor() - 1.0, 0.5 * (1.0 / g.scale_factor() - 1.0), 1e-9);
  // A known mass on a drive already corrected: only what was not applied then is in the scale.
  LearntGearMasses corrected = truck_gears();
  ASSERT_TRUE(corrected.restore(truth));
  corrected.add_reference(urban, m1, 1e-10, 1e-2, corrected);
  EXPECT_NEAR(corrected.scale_factor(), 1.0, 1e-9);
  // The interval: a drive in that mix at the reference's mass rests on no correction; at
  // another mass on the part the scale factor moves.
  EXPECT_NEAR(g.mass_variance_kg2(urban, m1), 0.0, 1e-3);
  EXPECT_GT(g.mass_variance_kg2(urban, 27000.0), 1.0);
  EXPECT_EQ(g.implausible(g.state()), "");
  GearMassesState bad = g.state();
  bad.reference_applied = 1e11;  // a level of -10: none the scale could hold
  EXPECT_NE(g.implausible(bad), "");
  g.reset();
  EXPECT_EQ(g.scale_factor(), 1.0);
  EXPECT_EQ(g.state().reference_share_per_kg[0], 0.0);
  EXPECT_EQ(g.state().reference_precision, 0.0);
}

TEST(LearntGearMassesTest, NothingIsLearntWithoutPerGearMassesOrWhenSwitchedOff) {
  EXPECT_EQ(LearntGearMasses({}, 0.3, 0.01, 20).gears(), 0);
  EXPECT_EQ(LearntGearMasses({300.0}, 0.3, 0.01, 20).gears(), 0);  // one gear: no difference
  VehicleParams v = testing::test_vehicle();
  v.rotating_mass_by_gear_kg = {400.0, 200.0};
  LearningParams learning;
  EXPECT_EQ(learnt_gear_masses_for(v, learning, 0.01).gears(), 2);
  learning.learn_gear_masses = false;
  EXPECT_EQ(learnt_gear_masses_for(v, learning, 0.01).gears(), 0);
  learning.learn_gear_masses = true;
  v.derive_overall_ratio = true;  // its plateaus are no gear numbers
  EXPECT_EQ(learnt_gear_masses_for(v, learning, 0.01).gears(), 0);
}

// Through the pipeline: a car whose config overstates its low gears' rotating masses (the
// engine's inertia reflected through them). Its drives in gears 1-2 read low, in gears 3-4
// right. No load sensor.
const std::vector<double> kCarConfigKg = {400.0, 200.0, 100.0, 50.0};
const std::vector<double> kCarTrueKg = {220.0, 150.0, 92.0, 48.0};

PipelineParams geared_car() {
  PipelineParams p = testing::learning_car();
  p.vehicle.rotating_mass_by_gear_kg = kCarConfigKg;
  return p;
}

/// A drive of 60 s in each of `gears`, on `mass_kg`, the gear reported on the bus.
std::vector<Sample> geared_drive(double mass_kg, const std::vector<int>& gears, double t0_s,
                                 unsigned seed, const VehicleParams& v) {
  std::vector<Sample> out;
  double t = t0_s;
  for (int gear : gears) {
    testing::LongitudinalDrive d;
    d.mass_kg = mass_kg;
    d.rotating_mass_kg = kCarTrueKg[std::size_t(gear - 1)];
    d.force_noise_std_n = 20.0;
    d.seed = seed++;
    std::vector<Sample> part = testing::longitudinal_samples(d, v, t, t + 60.0, 10.0, 0.0);
    for (Sample& s : part) s.set(Input::kGear, static_cast<double>(gear));
    out.insert(out.end(), part.begin(), part.end());
    t += 60.0;
  }
  return out;
}

double final_error(Pipeline& pipeline, const std::vector<Sample>& samples, double mass_kg) {
  for (const Sample& s : samples) pipeline.step(s);
  pipeline.flush();
  return pipeline.estimate().mass_kg / mass_kg - 1.0;
}

/// Five drives on other loads and gear mixes, each a power cycle after the one before, from
/// `start` (nullptr: a fresh car) at *t0_s, a day apart; the last one's snapshot.
PipelineSnapshot teach_gears(const PipelineParams& p, const PipelineSnapshot* start, unsigned seed,
                             double* t0_s) {
  const std::vector<std::vector<int>> mixes = {{3, 4}, {1, 2, 3}, {2, 3, 4}, {1, 3, 4}, {1, 2, 4}};
  PipelineSnapshot saved = start ? *start : PipelineSnapshot{};
  for (std::size_t d = 0; d < mixes.size(); ++d) {
    Pipeline drive(p);
    if (start || d > 0) {
      EXPECT_TRUE(drive.restore(saved)) << d;
    }
    const unsigned drive_seed = seed + unsigned(d) * 7;
    final_error(drive,
                geared_drive(1550.0 + 100.0 * double(d), mixes[d], *t0_s, drive_seed, p.vehicle),
                1.0);
    saved = drive.snapshot();
    *t0_s += 86400.0;
  }
  return saved;
}

TEST(LearntGearMassesTest, ACarsDrivesTeachTheGearsThatItsNextLowGearDriveUses) {
  const PipelineParams p = geared_car();
  const VehicleParams& v = p.vehicle;
  // Fresh, a drive in gears 1-2 reads low: its pairs carry less rotating mass than the config.
  // What two gears tell in the drive itself (PairTermSums) takes most of that off; the gears
  // learnt below are what a drive without that fit would need.
  PipelineParams unfitted = p;
  unfitted.estimator.fit_pair_terms = false;
  Pipeline fresh(unfitted);
  const double fresh_error = final_error(fresh, geared_drive(1650.0, {1, 2}, 0.0, 50, v), 1650.0);
  EXPECT_LT(fresh_error, -0.03);
  Pipeline fitted(p);
  const double fitted_error = final_error(fitted, geared_drive(1650.0, {1, 2}, 0.0, 50, v), 1650.0);
  EXPECT_LT(std::abs(fitted_error), 0.015);
  // A drive in one gear teaches nothing, and what it saves restores.
  Pipeline one_gear(p);
  final_error(one_gear, geared_drive(1650.0, {3}, 0.0, 60, v), 1650.0);
  Pipeline after_one_gear(p);
  EXPECT_TRUE(after_one_gear.restore(one_gear.snapshot()));
  EXPECT_EQ(one_gear.snapshot().gear_masses.drives, 0);

  // Drives on other loads and gear mixes, each a power cycle after the one before.
  double t0 = 0.0;
  const PipelineSnapshot saved = teach_gears(p, nullptr, 10, &t0);
  EXPECT_GE(saved.gear_masses.drives, 4);
  // The learnt gear 1 carries less than the config, by about what the truth says relative to
  // the top gear.
  const double learnt_1 = saved.gear_masses.correction_kg[0] - saved.gear_masses.correction_kg[3];
  EXPECT_NEAR(learnt_1, (kCarTrueKg[0] - kCarConfigKg[0]) - (kCarTrueKg[3] - kCarConfigKg[3]),
              60.0);

  // The same low-gear drive after them reads the mass, and its interval holds it.
  Pipeline later(p);
  ASSERT_TRUE(later.restore(saved));
  const double later_error = final_error(later, geared_drive(1650.0, {1, 2}, t0, 50, v), 1650.0);
  EXPECT_LT(std::abs(later_error), 0.5 * std::abs(fresh_error));
  // The estimate shows what is learnt (status_t's gears).
  EXPECT_EQ(later.estimate().learnt_gears, 4);
  EXPECT_EQ(later.estimate().learnt_gear_drives, later.gear_masses().state().drives);
  EXPECT_EQ(later.estimate().learnt_gear_correction_kg[0], later.gear_masses().correction_kg(1));
  EXPECT_EQ(later.estimate().learnt_gear_std_kg[3], later.gear_masses().correction_std_kg(4));
  EXPECT_LE(later.estimate().ci_low_kg, 1650.0);
  EXPECT_GE(later.estimate().ci_high_kg, 1650.0);

  // Switched off, the same lifetime teaches nothing and the drive reads as the fresh one (with
  // the fit that nothing learnt then leaves on).
  PipelineParams off = p;
  off.estimator.learning.learn_gear_masses = false;
  Pipeline unlearnt(off);
  PipelineSnapshot no_gears = saved;
  no_gears.gear_masses = GearMassesState{};
  ASSERT_TRUE(unlearnt.restore(no_gears));
  EXPECT_NEAR(final_error(unlearnt, geared_drive(1650.0, {1, 2}, t0, 50, v), 1650.0), fitted_error,
              0.01);
}

// A known mass on a light load in first gear, then drives that teach the gears: a heavy load in
// the same gear reads its mass. The known-mass drive's gear-mix level is in the learnt scale
// relative to its mass; taken off in kg at another mass it would be off by e (1/M2 - 1/M1).
TEST(LearntGearMassesTest, AKnownMassOnOneLoadHoldsOnAnother) {
  PipelineParams p = geared_car();
  p.vehicle.max_mass_kg = 3000.0;
  const VehicleParams& v = p.vehicle;
  const double light = 1550.0;
  const double heavy = 2900.0;
  Pipeline first(p);
  ASSERT_TRUE(first.declare_known_mass(light, 5.0));
  final_error(first, geared_drive(light, {1}, 0.0, 70, v), light);
  // The scale takes the low gear's level when the drive ends.
  EXPECT_LT(first.learnt_scale_if_ended().scale(), 0.95);
  const PipelineSnapshot known = first.snapshot();
  double t0 = 86400.0;
  const PipelineSnapshot saved = teach_gears(p, &known, 20, &t0);
  Pipeline later(p);
  ASSERT_TRUE(later.restore(saved));
  const double error = final_error(later, geared_drive(heavy, {1}, t0, 90, v), heavy);
  // The level the known-mass drive's gear reads, and what it would leave in kg at this mass.
  const double level_kg = kCarTrueKg[0] - kCarConfigKg[0];
  const double kg_offset_error = level_kg * (1.0 / heavy - 1.0 / light);
  EXPECT_GT(std::abs(kg_offset_error), 0.03);
  EXPECT_LT(std::abs(error), 0.2 * std::abs(kg_offset_error)) << error;  // 0.03 % against 5.4 %
  EXPECT_LE(later.estimate().ci_low_kg, heavy);
  EXPECT_GE(later.estimate().ci_high_kg, heavy);
}

}  // namespace
}  // namespace vmass
