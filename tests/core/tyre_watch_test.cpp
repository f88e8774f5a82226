// New tyres told by the car's launches: TyreWatch's step across drives, LaunchIntegrator's
// launch from a standstill, and LearntScale moving with a measured step.
#include "vmass/core/tyre_watch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "vmass/core/launch_integrator.hpp"
#include "vmass/core/learnt_scale.hpp"

namespace vmass {
namespace {

constexpr double kLaunchStd = 0.008;  // one launch's scatter of log s, as the lifetime reads it

/// `drives` drives of `launches` launches each, log s drawn about `log_ratio`; the verdicts.
std::vector<TyreVerdict> drive(TyreWatch* watch, int drives, int launches, double log_ratio,
                               std::mt19937* rng) {
  std::normal_distribution<double> scatter(0.0, kLaunchStd);
  std::vector<TyreVerdict> out;
  for (int d = 0; d < drives; ++d) {
    for (int i = 0; i < launches; ++i) {
      // Launches and stops by turns, the stops 3 % higher (the wheels' slip under the brakes).
      const bool stop = i % 2 == 1;
      watch->add_span(stop ? SpanKind::kStop : SpanKind::kLaunch,
                      10.0 * std::exp(log_ratio + (stop ? 0.03 : 0.0) + scatter(*rng)), 10.0);
    }
    out.push_back(watch->end_drive());
  }
  return out;
}

TEST(TyreWatchTest, TheSameTyresAreNoChangeHoweverLongTheyAreDriven) {
  std::mt19937 rng(7);
  TyreWatch watch(TyreWatchParams{});
  for (const TyreVerdict& v : drive(&watch, 60, 2, 0.012, &rng)) {
    EXPECT_FALSE(v.changed);
    EXPECT_LT(v.best_sigma, TyreWatchParams{}.change_sigma);
  }
  EXPECT_NEAR(watch.log_ratio(SpanKind::kLaunch), 0.012, 0.003);
  EXPECT_EQ(watch.state().changes, 0);
}

TEST(TyreWatchTest, NewTyresAreAStepFoundWithinAFewDrivesAndMeasured) {
  std::mt19937 rng(11);
  TyreWatch watch(TyreWatchParams{});
  drive(&watch, 5, 3, 0.0, &rng);
  const double step = std::log(1.025);  // the radius 2.5 % larger
  int found_after = -1;
  TyreVerdict found;
  for (int d = 0; d < 8 && found_after < 0; ++d) {
    const TyreVerdict v = drive(&watch, 1, 3, step, &rng).front();
    if (v.changed) {
      found_after = d + 1;
      found = v;
    }
  }
  ASSERT_GT(found_after, 0) << "not found in 8 drives of 3 launches";
  EXPECT_LE(found_after, 5);
  EXPECT_NEAR(found.log_step, step, 3.0 * std::sqrt(found.log_step_var));
  EXPECT_LT(std::sqrt(found.log_step_var), 0.008);
  EXPECT_EQ(watch.state().changes, 1);
  // The launches after the step are the belief now: the same tyres again are no change.
  for (const TyreVerdict& v : drive(&watch, 10, 2, step, &rng)) EXPECT_FALSE(v.changed);
  EXPECT_NEAR(watch.log_ratio(SpanKind::kLaunch), step, 0.004);
}

// Between a step's first signs and its confirmation, the interval holds it.
TEST(TyreWatchTest, AStepNotYetAChangeIsSuspectedAndTheSuspicionIsSaved) {
  std::mt19937 rng(13);
  TyreWatch watch(TyreWatchParams{});
  drive(&watch, 5, 3, 0.0, &rng);
  EXPECT_EQ(watch.suspected_variance(), 0.0);
  const TyreVerdict v = drive(&watch, 1, 3, std::log(1.02), &rng).front();
  ASSERT_FALSE(v.changed);
  ASSERT_GT(v.best_sigma, TyreWatchParams{}.suspect_sigma);
  EXPECT_NEAR(std::sqrt(watch.suspected_variance()), std::abs(v.log_step), 1e-12);
  EXPECT_NEAR(v.log_step, std::log(1.02), 0.012);
  TyreWatch restored(TyreWatchParams{});
  ASSERT_TRUE(restored.restore(watch.state()));
  EXPECT_DOUBLE_EQ(restored.suspected_variance(), watch.suspected_variance());
  EXPECT_DOUBLE_EQ(restored.standing().best_sigma, v.best_sigma);
  // A drive without a launch tells nothing new: the suspicion and the step shown stand.
  watch.end_drive();
  EXPECT_DOUBLE_EQ(watch.suspected_variance(), restored.suspected_variance());
  EXPECT_DOUBLE_EQ(watch.standing().log_step, v.log_step);
  EXPECT_EQ(watch.last_verdict().best_sigma, 0.0);  // what that drive's end found: nothing
}

TEST(TyreWatchTest, AStepSmallerThanTheMinimumIsNoChange) {
  std::mt19937 rng(3);
  TyreWatchParams params;
  params.launch_std = 0.001;  // so precise that a 0.4 % step is many sigma
  TyreWatch watch(params);
  std::normal_distribution<double> tiny(0.0, 0.0005);
  for (int d = 0; d < 10; ++d) {
    const double log_ratio = d < 5 ? 0.0 : 0.004;
    for (int i = 0; i < 5; ++i)
      watch.add_span(SpanKind::kLaunch, 10.0 * std::exp(log_ratio + tiny(rng)), 10.0);
    const TyreVerdict v = watch.end_drive();
    EXPECT_FALSE(v.changed);
    if (d == 9) {
      EXPECT_GT(v.best_sigma, params.change_sigma);
    }
  }
}

TEST(TyreWatchTest, ALaunchThatIsNoLaunchIsNotTaken) {
  TyreWatch watch(TyreWatchParams{});
  watch.add_span(SpanKind::kLaunch, 14.0, 10.0);  // 40 % off: no tyre does that
  watch.add_span(SpanKind::kLaunch, -1.0, 10.0);
  watch.add_span(SpanKind::kLaunch, 10.0, 0.0);
  watch.add_span(SpanKind::kLaunch, std::nan(""), 10.0);
  EXPECT_EQ(watch.state().drive.count(), 0.0);
  EXPECT_TRUE(std::isnan(watch.log_ratio(SpanKind::kLaunch)));
}

TEST(TyreWatchTest, DeclaredTyresStartTheLaunchesAgainSoTheStepIsNotTakenTwice) {
  std::mt19937 rng(5);
  TyreWatch watch(TyreWatchParams{});
  drive(&watch, 5, 3, 0.0, &rng);
  watch.tyres_declared();
  for (const TyreVerdict& v : drive(&watch, 6, 3, 0.03, &rng)) EXPECT_FALSE(v.changed);
  EXPECT_NEAR(watch.log_ratio(SpanKind::kLaunch), 0.03, 0.007);  // 3 std of 12 launches' mean
}

TEST(TyreWatchTest, ASavedStateIsRestoredOnlyWhenPlausible) {
  std::mt19937 rng(9);
  TyreWatch watch(TyreWatchParams{});
  drive(&watch, 3, 2, 0.01, &rng);
  TyreWatch other(TyreWatchParams{});
  ASSERT_TRUE(other.restore(watch.state()));
  EXPECT_DOUBLE_EQ(other.log_ratio(SpanKind::kStop), watch.log_ratio(SpanKind::kStop));
  TyreWatchState bad = watch.state();
  bad.window_drives = kTyreWatchWindowDrives + 1;
  EXPECT_FALSE(TyreWatch::implausible(bad).empty());
  bad = watch.state();
  bad.settled.kind[1].sum = std::nan("");
  EXPECT_FALSE(other.restore(bad));
  bad = watch.state();
  bad.window[0].kind[0].sum = 0.5 * bad.window[0].kind[0].count;  // a mean log s of 0.5
  EXPECT_FALSE(TyreWatch::implausible(bad).empty());
}

/// A 100 Hz drive whose speed signal reads v / tyre_factor and accelerometer a_x.
class Ticks {
 public:
  explicit Ticks(double tyre_factor) : tyre_factor_(tyre_factor) {}
  void add(double v, double a_x) {
    Sample s;
    s.time_us = t_;
    s.set(Input::kSpeed, v / tyre_factor_);
    s.set(Input::kAccelX, a_x);
    samples_.push_back(s);
    t_ += 10'000;
  }
  const std::vector<Sample>& samples() const { return samples_; }

 private:
  double tyre_factor_;
  std::vector<Sample> samples_;
  TimeUs t_ = 1'000'000;
};

/// 100 Hz ticks: `still_s` at rest on `grade_accel` (what the accelerometer reads at rest), then a
/// launch at `accel` until `end_mps`; the speed signal reads v / tyre_factor, the accelerometer
/// the true acceleration plus the grade (which may change by `grade_change` over the launch).
std::vector<Sample> launch(double still_s, double grade_accel, double accel, double end_mps,
                           double tyre_factor, double grade_change = 0.0) {
  Ticks ticks(tyre_factor);
  auto tick = [&](double v, double a_x) { ticks.add(v, a_x); };
  for (double s = 0.0; s < still_s; s += 0.01) tick(0.0, grade_accel);
  const double duration = end_mps / accel;
  for (double s = 0.01; s <= duration + 0.02; s += 0.01) {
    tick(accel * s, accel + grade_accel + grade_change * s / duration);
  }
  return ticks.samples();
}

LaunchSpan integrate(const std::vector<Sample>& samples, int* launches) {
  LaunchIntegrator integrator;
  LaunchSpan span;
  *launches = 0;
  for (const Sample& s : samples) {
    LaunchSpan one;
    if (integrator.step(s, &one)) {
      span = one;
      ++*launches;
    }
  }
  return span;
}

TEST(LaunchIntegratorTest, ALaunchOnAGradeMeasuresTheSpeedSignalsScale) {
  int launches = 0;
  const LaunchSpan span = integrate(launch(2.0, 0.6, 1.5, 12.0, 1.02), &launches);
  ASSERT_EQ(launches, 1);
  EXPECT_NEAR(span.accel_dv / span.wheel_dv, 1.02, 0.005);
}

TEST(LaunchIntegratorTest, AGradeThatChangesUnderTheLaunchIsNotTaken) {
  int launches = 0;
  integrate(launch(2.0, 0.0, 1.5, 12.0, 1.0, 0.3), &launches);
  EXPECT_EQ(launches, 0);
}

TEST(LaunchIntegratorTest, NoLaunchWithoutAStandstillLongEnoughToReadTheGrade) {
  int launches = 0;
  integrate(launch(0.5, 0.6, 1.5, 12.0, 1.0), &launches);
  EXPECT_EQ(launches, 0);
}

TEST(LaunchIntegratorTest, AHoleInTheDataEndsTheLaunch) {
  std::vector<Sample> samples = launch(2.0, 0.0, 1.5, 12.0, 1.0);
  for (std::size_t i = 300; i < samples.size(); ++i) samples[i].time_us += 500'000;
  int launches = 0;
  integrate(samples, &launches);
  EXPECT_EQ(launches, 0);
}

/// 100 Hz ticks: a cruise at `from_mps`, a stop at `decel` on `grade_accel`, then `rest_s` at
/// rest; the speed signal reads v / tyre_factor.
std::vector<Sample> stop(double from_mps, double decel, double grade_accel, double rest_s,
                         double tyre_factor) {
  Ticks ticks(tyre_factor);
  auto tick = [&](double v, double a_x) { ticks.add(v, a_x); };
  for (int i = 0; i < 200; ++i) tick(from_mps, grade_accel);
  for (double v = from_mps - decel * 0.01; v > 0.0; v -= decel * 0.01) tick(v, grade_accel - decel);
  for (double s = 0.0; s < rest_s; s += 0.01) tick(0.0, grade_accel);
  return ticks.samples();
}

TEST(LaunchIntegratorTest, AStopToRestMeasuresTheScaleOnceTheRestReadsTheGrade) {
  int spans = 0;
  const LaunchSpan span = integrate(stop(12.0, 1.5, -0.4, 2.0, 1.02), &spans);
  ASSERT_EQ(spans, 1);
  EXPECT_NEAR(span.accel_dv / span.wheel_dv, 1.02, 0.005);
  // Moving off again before the rest has read the grade: no stop.
  integrate(stop(12.0, 1.5, -0.4, 1.2, 1.02), &spans);
  EXPECT_EQ(spans, 0);
}

TEST(LearntScaleTest, MeasuredNewTyresMoveTheBeliefAndWhatItRestsOn) {
  LearntScale s(LearningParams{}, 0.035);
  s.add_evidence(std::log(1.01), 1e-4);
  s.add_anchor(std::log(1.012), 4e-4, 0.01);
  const double before = s.log_scale();
  const double var_before = s.state().log_scale_var;
  const double anchor_before = s.state().anchor_weighted_log_scale / s.state().anchor_weight;
  s.tyres_measured(0.02, 4e-5);
  EXPECT_NEAR(s.state().log_scale - std::log(1.01), 0.02, 1e-3);
  EXPECT_NEAR(s.state().log_scale_var, var_before + 4e-5, 1e-12);
  EXPECT_NEAR(s.state().anchor_weighted_log_scale / s.state().anchor_weight - anchor_before, 0.02,
              1e-12);
  EXPECT_NEAR(s.log_scale() - before, 0.02, 1e-3);
  EXPECT_EQ(s.state().tyre_changes, 0);  // declared changes only
}

}  // namespace
}  // namespace vmass
