// Why a block took no pair: every tick's verdict counted per block, the refusals most frequent
// first, their shares of the block's ticks as a reader sees them, and the replay summary's
// table and JSON that carry them. Counts are worked out by hand.
#include "vmass/scoring/verdict_tally.hpp"

#include <gtest/gtest.h>

#include "vmass/scoring/replay_summary.hpp"
#include "vmass/scoring/replay_summary_text.hpp"

namespace vmass::scoring {
namespace {

std::array<PairEvent, kBlockCount> events(PairVerdict longitudinal, PairVerdict lateral) {
  std::array<PairEvent, kBlockCount> e{};
  e[static_cast<std::size_t>(Block::kLongitudinal)].verdict = longitudinal;
  e[static_cast<std::size_t>(Block::kLateral)].verdict = lateral;
  return e;
}

// A cruise: 6 ticks whose force did not change, 3 too slow, 1 accepted.
VerdictTally cruise() {
  VerdictTally t;
  for (int i = 0; i < 6; ++i) t.add(events(PairVerdict::kSmallDeltaForce, PairVerdict::kDisabled));
  for (int i = 0; i < 3; ++i) t.add(events(PairVerdict::kSpeed, PairVerdict::kDisabled));
  t.add(events(PairVerdict::kAccepted, PairVerdict::kDisabled));
  return t;
}

TEST(VerdictTally, RefusalsComeMostFrequentFirstWithoutTheAccepted) {
  const VerdictTally t = cruise();
  const auto refused = t.refusals(Block::kLongitudinal);
  ASSERT_EQ(refused.size(), 2u);
  EXPECT_EQ(refused[0], std::make_pair(PairVerdict::kSmallDeltaForce, 6L));
  EXPECT_EQ(refused[1], std::make_pair(PairVerdict::kSpeed, 3L));
  EXPECT_EQ(t.counts(Block::kLongitudinal)[static_cast<std::size_t>(PairVerdict::kAccepted)], 1);
}

TEST(VerdictTally, SharesAreOfTheBlocksTicks) {
  const VerdictTally t = cruise();
  EXPECT_EQ(t.describe_refusals(Block::kLongitudinal), "small_delta_force 60.0 %, speed 30.0 %");
  EXPECT_EQ(t.describe_refusals(Block::kLongitudinal, 1), "small_delta_force 60.0 %");
  EXPECT_EQ(t.describe_refusals(Block::kLateral), "disabled 100.0 %");
  EXPECT_EQ(VerdictTally().describe_refusals(Block::kLongitudinal), "");
}

TEST(VerdictTally, TheReplaySummarySaysWhyNoPairWasTaken) {
  ReplaySummary summary(std::nullopt);
  Estimate e;
  e.status = EstimateStatus::kInitialising;
  e.mass_kg = 20000.0;
  for (int k = 0; k < 4; ++k) {
    e.time_us = k * 10'000;
    summary.add(e);
    summary.add_events(events(PairVerdict::kSmallDeltaForce, PairVerdict::kDisabled));
  }
  const ReplaySummary::Result r = summary.result();
  const std::string json = replay_json(r, "bayes");
  EXPECT_NE(json.find(R"("refused":{"small_delta_force":4})"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("refused":{"disabled":4})"), std::string::npos) << json;
}

}  // namespace
}  // namespace vmass::scoring
