// The supervisor's innovation gate: outliers are rejected once the belief is narrow, a wrong
// belief cannot lock itself in, and availability counts accepted pairs per tick and block.
#include "vmass/core/supervisor.hpp"

#include <random>

#include <gtest/gtest.h>

#include "vmass/core/rls_estimator.hpp"

namespace vmass {
namespace {

Extraction pair_of(double delta_accel, double y, Block block = Block::kLongitudinal) {
  Extraction e;
  e.verdict = PairVerdict::kAccepted;
  e.pair.block = block;
  e.pair.delta_accel_mps2 = delta_accel;
  e.pair.y_n = y;
  return e;
}

MassPrior prior(double mass) { return MassPrior{mass, 100.0, 0.0, 100.0}; }

TEST(Supervisor, RejectsOutliersOnceGatingStarts) {
  RlsParams rp;
  rp.noise_std_n = 20.0;
  RlsEstimator rls(rp);
  rls.reset(prior(1600.0));
  SupervisorParams sp;
  sp.min_pairs_before_gating = 30;
  Supervisor sup(sp);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 20.0);
  std::uniform_real_distribution<double> accel(-0.5, 0.5);
  bool changed = false;
  for (int i = 0; i < 200; ++i) {
    const double da = accel(rng);
    const PairEvent ev =
        sup.offer(Block::kLongitudinal, pair_of(da, 1650.0 * da + noise(rng)), rls, &changed);
    EXPECT_EQ(ev.verdict, PairVerdict::kAccepted) << i;  // honest pairs pass
  }
  const double before = rls.state().mass_kg;
  // A gear-shift torque spike: 2000 N where 1650 * 0.1 = 165 N is expected.
  const PairEvent spike = sup.offer(Block::kLongitudinal, pair_of(0.1, 2000.0), rls, &changed);
  EXPECT_EQ(spike.verdict, PairVerdict::kInnovation);
  EXPECT_GT(spike.test_ratio, sp.innovation_gate_sigma);
  EXPECT_EQ(rls.state().mass_kg, before);
  EXPECT_EQ(sup.counters(Block::kLongitudinal).rejected_innovation, 1);
  EXPECT_EQ(sup.counters(Block::kLongitudinal).accepted, 200);
}

TEST(Supervisor, AWrongBeliefCannotLockItselfIn) {
  RlsParams rp;
  rp.noise_std_n = 5.0;
  RlsEstimator rls(rp);
  rls.reset(MassPrior{1200.0, 1.0, 0.0, 1.0});  // confidently wrong: the car is 1650 kg
  SupervisorParams sp;
  sp.min_pairs_before_gating = 0;
  sp.max_consecutive_rejections = 10;
  Supervisor sup(sp);
  bool changed = false;
  int accepted = 0;
  for (int i = 0; i < 110; ++i) {
    const double da = (i % 2 == 0) ? 0.4 : -0.4;
    const PairEvent ev = sup.offer(Block::kLongitudinal, pair_of(da, 1650.0 * da), rls, &changed);
    accepted += ev.verdict == PairVerdict::kAccepted;
  }
  // Every 11th pair is let through after 10 rejections in a row.
  EXPECT_EQ(accepted, 10);
  EXPECT_GT(rls.state().mass_kg, 1200.0);
}

TEST(Supervisor, AvailabilityIsAcceptedPairsPerTickAndBlock) {
  RlsEstimator rls(RlsParams{});
  rls.reset(prior(1600.0));
  Supervisor sup(SupervisorParams{});
  bool changed = false;
  Extraction none;
  none.verdict = PairVerdict::kSmallDeltaAccel;
  for (int i = 0; i < 100; ++i) {
    sup.offer(Block::kLongitudinal, i % 4 == 0 ? pair_of(0.2, 320.0) : none, rls, &changed);
    sup.offer(Block::kLateral, none, rls, &changed);
  }
  EXPECT_DOUBLE_EQ(sup.counters(Block::kLongitudinal).availability(), 0.25);
  EXPECT_EQ(sup.counters(Block::kLongitudinal).ticks, 100);
  EXPECT_DOUBLE_EQ(sup.counters(Block::kLateral).availability(), 0.0);
  EXPECT_TRUE(changed);
}

}  // namespace
}  // namespace vmass
