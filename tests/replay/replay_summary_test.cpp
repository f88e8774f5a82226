// What vmass-replay reports must be true: empty CSV cells before the first estimate, no
// "within 1 %" claim for a prior, the prior labelled as one, pairs used and accepted apart, the
// flushed batch in the final estimate, and the JSON carrying what the table shows (the truth's
// time-base rule: tests/scoring/truth_test.cpp).
#include <string>

#include <gtest/gtest.h>

#include "vmass/csv/estimate_csv.hpp"
#include "vmass/json/json.hpp"
#include "vmass/scoring/replay_summary.hpp"
#include "vmass/scoring/replay_summary_text.hpp"

namespace vmass {
namespace {

using scoring::ReplaySummary;
using scoring::Truth;

std::string table_of(const ReplaySummary& s, const std::string& name) {
  return scoring::replay_table(s.result(), name);
}
/// The JSON object, parsed (a line: no newline in it).
json::Json json_of(const ReplaySummary& s, const std::string& name) {
  const std::string text = scoring::replay_json(s.result(), name);
  EXPECT_EQ(text.find('\n'), std::string::npos) << text;
  return json::Json::parse(text);
}

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
  EXPECT_FALSE(r.time_within_since_first_tick_s[2].has_value());  // 1 %
  EXPECT_FALSE(r.time_within_since_first_tick_s[0].has_value());  // 5 %
  const std::string table = table_of(summary, "bayes");
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
  EXPECT_TRUE(contains(table_of(summary, "rls"), "(no-static prior: driving began before any"));
  EXPECT_EQ(json_of(summary, "rls")["prior"], "no_static_prior");
}

TEST(ReplaySummary, WithPairsTheTimeWithinCountsFromTheLastExcursion) {
  ReplaySummary summary(constant_truth(1700.0, 0.0, 10.0));
  summary.add(static_prior(0));                    // 2.9 % low: outside 2 % and 1 %
  summary.add(refined(10'000, 1690.0, 100, 100));  // 0.59 % low
  summary.add(refined(20'000, 1702.0, 200, 200));
  const ReplaySummary::Result r = summary.result();
  const auto& within = r.time_within_since_first_tick_s;  // 5, 2, 1 %
  ASSERT_TRUE(within[0] && within[1] && within[2]);
  EXPECT_DOUBLE_EQ(*within[0], 0.0);
  EXPECT_DOUBLE_EQ(*within[2], 0.0);  // last outside at 0 s: within from then on
  EXPECT_DOUBLE_EQ(*r.coverage_of_dynamic_ticks, 1.0);
}

TEST(ReplaySummary, PairsUsedAndAcceptedAreReportedApart) {
  ReplaySummary summary(std::nullopt);
  summary.add(refined(0, 1700.0, 100, 130));
  const std::string table = table_of(summary, "bayes");
  EXPECT_TRUE(contains(table, "pairs used           100 (in the estimate)")) << table;
  EXPECT_TRUE(contains(table, "pairs accepted       130 (by the supervisor)")) << table;
  const json::Json j = json_of(summary, "bayes");
  EXPECT_EQ(j["pairs_used"], 100) << j;
  EXPECT_EQ(j["pairs_accepted"], 130) << j;
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
  const json::Json j = json_of(summary, "bayes");
  EXPECT_EQ(j["initial_mass_kg"], 1650.0) << j;
  EXPECT_EQ(j["prior"], "static_initialised") << j;
  EXPECT_EQ(j["reason"], "refining") << j;
  EXPECT_EQ(j["status"], "converging") << j;
  EXPECT_EQ(j["mass_std_kg"], 40.0) << j;
  const json::Json longitudinal = {{"ticks", 1},
                                   {"candidates", 133},
                                   {"accepted", 130},
                                   {"rejected_innovation", 3},
                                   {"refused", json::Json::object()}};  // no verdict added
  EXPECT_EQ(j["longitudinal"], longitudinal) << j;
  EXPECT_EQ(j["lateral"]["ticks"], 0) << j;
  EXPECT_EQ(j["ticks"], 1) << j;
  EXPECT_EQ(j["reinitialisations"], 0) << j;
  EXPECT_EQ(j["true_mass_kg"], 1700.0) << j;
  EXPECT_EQ(j["coverage"], 1.0) << j;
}

// What the drive taught about each gear's rotating mass, in both the table and the JSON; the
// learnt scale's row only when a known mass made it evidence.
TEST(ReplaySummary, TheLearntGearMassesAreShownInTheTableAndTheJson) {
  ReplaySummary summary(constant_truth(1700.0, 0.0, 10.0));
  summary.add(refined(0, 1690.0, 100, 130));
  ReplaySummary::Result::Learnt learnt;
  learnt.gear_drives = 2;
  learnt.gear_correction_kg = {-120.4, -9.6};
  learnt.gear_std_kg = {30.2, 5.0};
  summary.set_learnt(learnt);
  const std::string table = table_of(summary, "bayes");
  EXPECT_NE(table.find("learnt gear masses   from 2 drives: gear 1 -120 +- 30 kg, gear 2 -10 +- "
                       "5 kg\n"),
            std::string::npos)
      << table;
  EXPECT_EQ(table.find("learnt scale"), std::string::npos) << table;
  const json::Json j = json_of(summary, "bayes");
  EXPECT_EQ(j["learnt"]["gear_drives"], 2) << j;
  ASSERT_EQ(j["learnt"]["gears"].size(), 2u) << j;
  EXPECT_EQ(j["learnt"]["gears"][0]["gear"], 1) << j;
  EXPECT_DOUBLE_EQ(j["learnt"]["gears"][0]["correction_kg"].get<double>(), -120.4) << j;
  EXPECT_DOUBLE_EQ(j["learnt"]["gears"][1]["std_kg"].get<double>(), 5.0) << j;
}

// A drive whose standstill reading anchored the scale, no known mass: the row says so.
TEST(ReplaySummary, AScaleFromStandstillReadingsSaysSo) {
  ReplaySummary summary(constant_truth(1700.0, 0.0, 10.0));
  summary.add(refined(0, 1690.0, 100, 130));
  ReplaySummary::Result::Learnt learnt;
  learnt.scale = 0.9812;
  learnt.relative_std = 0.0231;
  learnt.anchors = 3;
  summary.set_learnt(learnt);
  const std::string table = table_of(summary, "bayes");
  EXPECT_NE(table.find("learnt scale         0.9812 (std 2.31 %, from 3 standstill readings of "
                       "the load)\n"),
            std::string::npos)
      << table;
  const json::Json j = json_of(summary, "bayes");
  EXPECT_EQ(j["learnt"]["anchors"], 3) << j;
  EXPECT_EQ(j["learnt"]["evidence"], 0) << j;
}

TEST(ReplaySummary, ACoarseSpeedSignalIsNamed) {
  ReplaySummary summary(std::nullopt);
  summary.add(refined(0, 21000.0, 100, 130));
  EXPECT_EQ(table_of(summary, "bayes").find("speed signal"), std::string::npos);
  EXPECT_FALSE(json_of(summary, "bayes").contains("speed_signal"));
  summary.set_coarse_speed(0.3124);
  const std::string table = table_of(summary, "bayes");
  EXPECT_NE(table.find("speed signal         changes every 0.31 s as the speed changes: too "
                       "coarse for its derivative, the rotating term read the accelerometer\n"),
            std::string::npos)
      << table;
  const json::Json j = json_of(summary, "bayes");
  EXPECT_EQ(j["speed_signal"]["coarse"], true) << j;
  EXPECT_EQ(j["speed_signal"]["rotating_accel"], "accelerometer") << j;
}

// The drive's own fit of the configured rotating masses' and converter map's errors: the
// converter's row only when some pair held its multiplication.
TEST(ReplaySummary, ThePairTermFitIsShownInTheTableAndTheJson) {
  ReplaySummary summary(std::nullopt);
  summary.add(refined(0, 21000.0, 100, 130));
  EXPECT_EQ(table_of(summary, "bayes").find("pair-term fit"), std::string::npos);
  EXPECT_FALSE(json_of(summary, "bayes").contains("pair_term_fit"));
  PairTermFit fit;
  fit.rotating_error = -0.1234;
  fit.rotating_error_std = 0.0456;
  fit.converter_error_std = 0.1443;
  fit.mass_shift_kg = -512.4;
  fit.mass_std_kg = 230.6;
  fit.pairs = 4807;
  summary.set_pair_terms(fit);
  std::string table = table_of(summary, "bayes");
  EXPECT_NE(table.find("pair-term fit        rotating masses -0.123 +- 0.046: mass -512 +- 231 kg "
                       "(4807 pairs)\n"),
            std::string::npos)
      << table;
  json::Json j = json_of(summary, "bayes");
  EXPECT_DOUBLE_EQ(j["pair_term_fit"]["rotating_error"].get<double>(), -0.1234) << j;
  EXPECT_DOUBLE_EQ(j["pair_term_fit"]["mass_shift_kg"].get<double>(), -512.4) << j;
  EXPECT_EQ(j["pair_term_fit"]["converter_multiplied"], false) << j;
  EXPECT_EQ(j["pair_term_fit"]["pairs"], 4807) << j;
  fit.converter_multiplied = true;
  fit.converter_error = -0.187;  // the map's multiplication 18.7 % low
  summary.set_pair_terms(fit);
  table = table_of(summary, "bayes");
  EXPECT_NE(table.find("rotating masses -0.123 +- 0.046, converter map +0.187 +- 0.144: mass"),
            std::string::npos)
      << table;
}

TEST(ReplaySummary, JsonHasNoMassBeforeAnyEstimate) {
  ReplaySummary summary(std::nullopt);
  summary.add(no_prior_yet(0));
  const json::Json j = json_of(summary, "bayes");
  EXPECT_EQ(j["has_estimate"], false) << j;
  EXPECT_TRUE(j["mass_kg"].is_null()) << j;
}

}  // namespace
}  // namespace vmass
