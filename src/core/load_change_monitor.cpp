#include "vmass/core/load_change_monitor.hpp"

#include <cmath>

#include "vmass/core/param_check.hpp"

namespace vmass {

std::string LoadChangeParams::validate() const {
  ParamCheck c("estimator.load_change");
  c.non_negative("min_stop_s", min_stop_s);
  c.positive("decide_sigma", decide_sigma);
  c.non_negative("min_change_fraction", min_change_fraction);
  if (min_pairs < 1) c.fail("min_pairs", "must be >= 1");
  if (batch_size < 0) c.fail("batch_size", "must be >= 0 (0: the estimator's bayes.batch_size)");
  if (!(change_prior > 0.0 && change_prior < 1.0)) c.fail("change_prior", "must be in (0, 1)");
  return c.message();
}

namespace {

BayesParams challenger_bayes_params(BayesParams bayes, int batch_size) {
  if (batch_size > 0) bayes.batch_size = batch_size;
  return bayes;
}

}  // namespace

LoadChangeMonitor::LoadChangeMonitor(const LoadChangeParams& params, const RlsParams& rls,
                                     const BayesParams& bayes, const SupervisorParams& supervisor,
                                     bool use_rls, const MassPrior& start_prior,
                                     double empty_mass_kg, double standstill_speed_mps)
    : params_(params),
      rls_(rls),
      bayes_(challenger_bayes_params(bayes, params.batch_size)),
      supervisor_(supervisor),
      use_rls_(use_rls),
      start_prior_(start_prior),
      empty_mass_kg_(empty_mass_kg),
      standstill_speed_mps_(standstill_speed_mps) {}

MassRegressor& LoadChangeMonitor::regressor() {
  return use_rls_ ? static_cast<MassRegressor&>(rls_) : static_cast<MassRegressor&>(bayes_);
}

const MassRegressor& LoadChangeMonitor::challenger() const {
  return use_rls_ ? static_cast<const MassRegressor&>(rls_)
                  : static_cast<const MassRegressor&>(bayes_);
}

bool LoadChangeMonitor::step(const Sample& sample) {
  if (!params_.detect_in_motion || !sample.has(Input::kSpeed)) return false;
  const bool still = std::abs(sample.speed_mps) <= standstill_speed_mps_;
  if (still) {
    if (!standing_) {
      standing_ = true;
      standing_since_us_ = sample.time_us;
    }
    if (to_seconds(sample.time_us - standing_since_us_) >= params_.min_stop_s) long_stop_ = true;
    return false;
  }
  standing_ = false;
  if (!long_stop_) return false;
  // Driving again after a stop that may have changed the load.
  long_stop_ = false;
  ended_active_ = active_;
  if (active_) ended_ = challenger().state();
  regressor().reset(start_prior_);
  supervisor_.on_regressor_reset();
  active_ = true;
  return true;
}

void LoadChangeMonitor::offer(Block block, const Extraction& extraction) {
  if (!active_) return;
  bool changed = false;
  supervisor_.offer(block, extraction, regressor(), &changed);
}

bool LoadChangeMonitor::contradicts(const RegressorState& main) const {
  if (!active_) return false;
  const RegressorState c = challenger().state();
  if (c.pairs_used < params_.min_pairs) return false;
  const double difference = std::abs(c.mass_kg - main.mass_kg);
  return difference > params_.min_change_fraction * empty_mass_kg_ &&
         difference > params_.decide_sigma * std::hypot(c.mass_std_kg, main.mass_std_kg);
}

bool LoadChangeMonitor::ended_in_suspicion(const RegressorState& main) const {
  return ended_active_ && ended_.pairs_used >= params_.min_pairs && reads_apart(ended_, main);
}

bool LoadChangeMonitor::undecided() const {
  return active_ && challenger().state().pairs_used < params_.min_pairs;
}

bool LoadChangeMonitor::suspects(const RegressorState& main) const {
  if (!active_) return false;
  const RegressorState c = challenger().state();
  return c.pairs_used > 0 && reads_apart(c, main);
}

bool LoadChangeMonitor::reads_apart(const RegressorState& reading,
                                    const RegressorState& belief) const {
  const bool outside = belief.mass_kg < reading.ci_low_kg || belief.mass_kg > reading.ci_high_kg;
  return outside &&
         std::abs(reading.mass_kg - belief.mass_kg) > params_.min_change_fraction * empty_mass_kg_;
}

}  // namespace vmass
