// What vmass-replay reports must be true: empty CSV cells before the first estimate, no
// "within 1 %" claim for a prior, the prior labelled as one, pairs used and accepted apart, the
// flushed batch in the final estimate, a truth refused when its time base is not the input's,
// and the JSON carrying what the table shows.
#include "replay_summary.hpp"

#include <string>

#include <gtest/gtest.h>

#include "vmass/csv/estimate_csv.hpp"

namespace vmass {
namespace {

Estimate no_prior_yet(TimeUs t) {
  Estimate e;
  e.time_us = t;
  return e;
}

/// A static prior of 1650 kg (std 40 kg), no pair used yet.
Estimate static_prior(TimeUs t) {
  Estimate e;
  e.time_us = t;
  e.mass_known = true;
  e.mass_kg = 1650.0;
  e.mass_std_kg = 40.0;
  e.ci_low_kg = 1571.6;
  e.ci_high_kg = 1728.4;
  e.initial_mass_kg = 1650.0;
  e.prior_reason = StatusReason::kStaticInitialised;
  e.status = EstimateStatus::kStaticOnly;
  e.reason = StatusReason::kStaticInitialised;
  return e;
}

Estimate refined(TimeUs t, double mass_kg, long pairs_used, long accepted) {
  Estimate e = static_prior(t);
  e.mass_kg = mass_kg;
  e.ci_low_kg = mass_kg - 10.0;
  e.ci_high_kg = mass_kg + 10.0;
  e.pairs_used = pairs_used;
  e.blocks[0].accepted = accepted;
  e.blocks[0].ticks = t / 10'000 + 1;
  e.blocks[0].candidates = accepted + 3;
  e.blocks[0].rejected_innovation = 3;
  e.status = EstimateStatus::kConverging;
  e.reason = StatusReason::kRefining;
  return e;
}

Truth constant_truth(double mass_kg, double from_s, double to_s) {
  return Truth({from_seconds(from_s), from_seconds(to_s)}, {mass_kg, mass_kg});
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(EstimateCsv, BeliefCellsAreEmptyBeforeTheFirstEstimate) {
  EXPECT_EQ(EstimateCsvWriter::row(no_prior_yet(0)),
            "0.00,,,,,initialising,,waiting_for_standstill,0,0,0.00000,0.00000,");
  EXPECT_EQ(EstimateCsvWriter::row(static_prior(from_seconds(1.5))),
            "1.50,1650.000,1571.600,1728.400,0.000,static_only,40.000,static_initialised,0,0,"
            "0.00000,0.00000,1650.000");
}

TEST(ReplaySummary, APriorIsLabelledAndClaimsNoTimeWithin) {
  // Given a truth equal to the static prior, when no pair is ever used, then the summary says the
  // final mass is the prior and claims no time from which the estimate is within 1 %.
  ReplaySummary summary(constant_truth(1650.0, 0.0, 10.0));
  summary.add(no_prior_yet(0));
  for (int k = 1; k <= 100; ++k) summary.add(static_prior(k * 10'000));
  const ReplaySummary::Result r = summary.result();
  EXPECT_FALSE(r.time_within_1_s.has_value());
  EXPECT_FALSE(r.time_within_5_s.has_value());
  const std::string table = summary.table("bayes");
  EXPECT_TRUE(contains(table, "1650.0 kg (the prior: no pair used)")) << table;
  EXPECT_TRUE(contains(table, "prior                1650.0 kg (static prior, eq. 3)")) << table;
  EXPECT_TRUE(contains(table, "within 1% from       n/a (no pair used")) << table;
  EXPECT_FALSE(contains(table, "static)")) << table;
}

TEST(ReplaySummary, NoStaticPriorIsNamedAsSuch) {
  ReplaySummary summary(std::nullopt);
  Estimate e = static_prior(0);
  e.prior_reason = StatusReason::kNoStaticPrior;
  summary.add(e);
  EXPECT_TRUE(contains(summary.table("rls"), "(no-static prior: driving began before any"));
  EXPECT_TRUE(contains(summary.json("rls"), "\"prior\": \"no_static_prior\""));
}

TEST(ReplaySummary, WithPairsTheTimeWithinCountsFromTheLastExcursion) {
  ReplaySummary summary(constant_truth(1700.0, 0.0, 10.0));
  summary.add(static_prior(0));                    // 2.9 % low: outside 2 % and 1 %
  summary.add(refined(10'000, 1690.0, 100, 100));  // 0.59 % low
  summary.add(refined(20'000, 1702.0, 200, 200));
  const ReplaySummary::Result r = summary.result();
  ASSERT_TRUE(r.time_within_5_s && r.time_within_2_s && r.time_within_1_s);
  EXPECT_DOUBLE_EQ(*r.time_within_5_s, 0.0);
  EXPECT_DOUBLE_EQ(*r.time_within_1_s, 0.0);  // last outside at 0 s: within from then on
  EXPECT_DOUBLE_EQ(*r.coverage, 1.0);
}

TEST(ReplaySummary, PairsUsedAndAcceptedAreReportedApart) {
  ReplaySummary summary(std::nullopt);
  summary.add(refined(0, 1700.0, 100, 130));
  const std::string table = summary.table("bayes");
  EXPECT_TRUE(contains(table, "pairs used           100 (in the estimate)")) << table;
  EXPECT_TRUE(contains(table, "pairs accepted       130 (by the supervisor)")) << table;
  const std::string json = summary.json("bayes");
  EXPECT_TRUE(contains(json, "\"pairs_used\": 100, \"pairs_accepted\": 130")) << json;
}

TEST(ReplaySummary, FinishReplacesTheFinalEstimateWithoutATick) {
  // The flushed estimate at the end of a log (the open Bayes batch taken in) is what is reported.
  ReplaySummary summary(constant_truth(1700.0, 0.0, 10.0));
  summary.add(refined(0, 1690.0, 100, 130));
  summary.add(refined(10'000, 1690.0, 100, 130));
  summary.finish(refined(10'000, 1699.0, 130, 130));
  const ReplaySummary::Result r = summary.result();
  EXPECT_EQ(r.ticks, 2);
  EXPECT_EQ(r.final_estimate.pairs_used, 130);
  EXPECT_NEAR(*r.error_percent, 100.0 * (1699.0 - 1700.0) / 1700.0, 1e-12);
}

TEST(ReplaySummary, JsonCarriesWhatTheTableShows) {
  ReplaySummary summary(constant_truth(1700.0, 0.0, 10.0));
  summary.add(refined(0, 1690.0, 100, 130));
  const std::string json = summary.json("bayes");
  for (const char* key :
       {"\"initial_mass_kg\": 1650.000", "\"prior\": \"static_initialised\"",
        "\"reason\": \"refining\"", "\"status\": \"converging\"", "\"mass_std_kg\": 40.000",
        "\"longitudinal\": {\"ticks\": 1, \"candidates\": 133, \"accepted\": 130, "
        "\"rejected_innovation\": 3}",
        "\"lateral\": {\"ticks\": 0", "\"ticks\": 1", "\"reinitialisations\": 0",
        "\"true_mass_kg\": 1700.000", "\"coverage\": 1.00000"}) {
    EXPECT_TRUE(contains(json, key)) << key << " missing from " << json;
  }
}

TEST(ReplaySummary, JsonHasNoMassBeforeAnyEstimate) {
  ReplaySummary summary(std::nullopt);
  summary.add(no_prior_yet(0));
  const std::string json = summary.json("bayes");
  EXPECT_TRUE(contains(json, "\"has_estimate\": false, \"mass_kg\": null")) << json;
}

TEST(Truth, TimeBaseMustContainTheFirstTick) {
  const Truth truth = constant_truth(1700.0, 0.0, 60.0);
  const TimeUs tick = 10'000;
  EXPECT_EQ(truth.check_time_base(0, tick), "");
  EXPECT_EQ(truth.check_time_base(-tick, tick), "");  // one tick early: tolerated
  EXPECT_EQ(truth.check_time_base(from_seconds(60.0), tick), "");
  // A candump log recorded on a car: epoch times.
  const std::string epoch = truth.check_time_base(from_seconds(1.7e9), tick);
  EXPECT_TRUE(contains(epoch, "0.000 to 60.000 s")) << epoch;
  EXPECT_TRUE(contains(epoch, "1700000000.000 s")) << epoch;
  EXPECT_NE(truth.check_time_base(-2 * tick, tick), "");
}

}  // namespace
}  // namespace vmass
