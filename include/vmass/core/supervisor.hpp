// Supervisor: decides which extracted pairs reach the regressor, and with what weight (paper
// Fig. 3, eq. 13).
//
// The extractors apply the activation conditions C1 (Table II) and C2 (Table III) and an
// outlier gate that does not depend on the estimate (the mass a pair implies must be
// plausible). The supervisor then weighs each pair by how well the current belief predicts it,
// a Huber M-estimator:
//   nu = y - phi theta_hat,  S = predicted variance of y (the belief's spread and the pair's
//   measured noise),  t = |nu| / sqrt(S)
//   weight x min(1, huber_k / t)
// so that a pair the belief cannot explain (an A/C compressor switching, a kerb, a shift the
// gates missed) counts less, without ever being thrown away: a drifted belief still feels the
// informative pairs that contradict it, and cannot lock itself in. A hard gate remains for the
// absurd (t > innovation_gate_sigma, default 20): rejected, except after
// max_consecutive_rejections in a row. Both act only after min_pairs_before_gating pairs since
// a (re)start, while the belief is still the wide prior.
//
// It also counts, per block, the ticks, the candidates, the accepted pairs and the innovation
// rejections: availability = accepted / ticks.
//
// Not thread-safe; no allocation.
#pragma once

#include <array>
#include <string>

#include "vmass/core/extraction.hpp"
#include "vmass/core/mass_regressor.hpp"

namespace vmass {

struct SupervisorParams {
  double innovation_gate_sigma = 20.0;
  double huber_k = 2.5;  ///< 0: no down-weighting
  int min_pairs_before_gating = 30;
  int max_consecutive_rejections = 50;

  std::string validate() const;
};

struct BlockCounters {
  long ticks = 0;
  long candidates = 0;  ///< pairs that passed the block's gates
  long accepted = 0;    ///< pairs handed to the regressor
  long rejected_innovation = 0;
  double availability() const {
    return ticks > 0 ? static_cast<double>(accepted) / static_cast<double>(ticks) : 0.0;
  }
};

/// One diagnostic record per tick and block (published on the debug channel).
struct PairEvent {
  RegressionPair pair;
  PairVerdict verdict = PairVerdict::kWarmingUp;
  double predicted_y_n = 0.0;
  double innovation_variance_n2 = 0.0;
  double test_ratio = 0.0;  ///< |nu| / sqrt(S)
  bool has_candidate = false;
};

class Supervisor {
 public:
  explicit Supervisor(const SupervisorParams& params);

  /// Offer one block's extraction for this tick to `regressor`. Returns the diagnostic record;
  /// `*estimate_changed` is set when the regressor's published state changed.
  PairEvent offer(Block block, const Extraction& extraction, MassRegressor& regressor,
                  bool* estimate_changed);
  /// A pair released later than its tick (the lag had to be identified first): counted as a
  /// candidate and accepted or rejected like any other, but not as a tick of its own.
  PairEvent offer_late(Block block, const Extraction& extraction, MassRegressor& regressor,
                       bool* estimate_changed);

  /// The regressor was reset (new prior): the gate opens again.
  void on_regressor_reset();

  const BlockCounters& counters(Block b) const { return counters_[static_cast<int>(b)]; }
  void restore_counters(Block b, const BlockCounters& c) { counters_[static_cast<int>(b)] = c; }

 private:
  SupervisorParams params_;
  std::array<BlockCounters, kBlockCount> counters_{};
  long pairs_since_reset_ = 0;
  int consecutive_rejections_ = 0;
};

}  // namespace vmass
