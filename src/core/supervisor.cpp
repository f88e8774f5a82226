#include "vmass/core/supervisor.hpp"

#include <cmath>

#include "vmass/core/param_check.hpp"

namespace vmass {

std::string SupervisorParams::validate() const {
  ParamCheck c("estimator.supervisor");
  c.positive("innovation_gate_sigma", innovation_gate_sigma);
  c.non_negative("huber_k", huber_k);
  c.at_least("min_pairs_before_gating", min_pairs_before_gating, 0);
  c.at_least("max_consecutive_rejections", max_consecutive_rejections, 1);
  return c.message();
}

Supervisor::Supervisor(const SupervisorParams& params) : params_(params) {}

void Supervisor::on_regressor_reset() {
  pairs_since_reset_ = 0;
  consecutive_rejections_ = 0;
}

PairEvent Supervisor::offer(Block block, const Extraction& extraction, MassRegressor& regressor,
                            bool* estimate_changed) {
  ++counters_[static_cast<int>(block)].ticks;
  return offer_late(block, extraction, regressor, estimate_changed);
}

PairEvent Supervisor::offer_late(Block block, const Extraction& extraction,
                                 MassRegressor& regressor, bool* estimate_changed) {
  BlockCounters& counters = counters_[static_cast<int>(block)];
  PairEvent event;
  event.verdict = extraction.verdict;
  if (!extraction.has_pair()) return event;

  event.has_candidate = true;
  event.pair = extraction.pair;
  ++counters.candidates;
  const PairPrediction prediction = regressor.predict(extraction.pair);
  event.predicted_y_n = prediction.y_n;
  event.innovation_variance_n2 = prediction.variance_n2;
  const double innovation = extraction.pair.y_n - prediction.y_n;
  event.test_ratio =
      prediction.variance_n2 > 0.0 ? std::abs(innovation) / std::sqrt(prediction.variance_n2) : 0.0;
  const bool gating = pairs_since_reset_ >= params_.min_pairs_before_gating;
  const bool outlier = gating && !(event.test_ratio <= params_.innovation_gate_sigma);
  if (outlier && consecutive_rejections_ < params_.max_consecutive_rejections) {
    ++consecutive_rejections_;
    ++counters.rejected_innovation;
    event.verdict = PairVerdict::kInnovation;
    return event;
  }
  consecutive_rejections_ = 0;
  RegressionPair pair = extraction.pair;
  if (gating && params_.huber_k > 0.0 && event.test_ratio > params_.huber_k) {
    pair.weight *= params_.huber_k / event.test_ratio;
  }
  event.pair = pair;
  if (regressor.update(pair)) *estimate_changed = true;
  ++pairs_since_reset_;
  ++counters.accepted;
  event.verdict = PairVerdict::kAccepted;
  return event;
}

}  // namespace vmass
