// LoadChangeMonitor: detects, from the drive itself, a load change that no deflection sensor saw
// (a car without one, or with a self-levelling axle).
//
// Load changes only at a standstill. After every standstill of at least min_stop_s, a
// challenger regressor (the same kind as the estimator's) starts from the no-static prior and
// learns from the pairs that follow, unweighted by the main belief; its pairs come from their
// own extractors. A supervisor of its own weighs them against the challenger's own belief, as
// the main one does the belief's: an unmodelled force (a retarder, a shift the gates missed)
// that the main belief refuses must not decide the challenger. The main belief keeps everything
// the earlier drive taught. "Main" below is the main belief as it was when the challenger
// started: the pairs since the stop would pull the running belief towards the challenger and
// hide the change. When the two disagree beyond chance,
//   |M_challenger - M_main| > decide_sigma sqrt(s_challenger^2 + s_main^2)
//   and > min_change_fraction M_empty, after min_pairs pairs of the challenger,
// the load changed at that stop: the challenger's belief becomes the estimate. Before that, once
// the challenger's own 95 % interval excludes the main estimate (by more than
// min_change_fraction M_empty), the change is suspected: the pipeline then publishes the
// challenger's mass with an interval that spans both beliefs (suspects()), since the drive
// since the stop says the main one may no longer hold. A later stop
// restarts the challenger; when nothing changed it simply agrees with the main belief and is
// dropped at the next stop. What the challenger a restart ends had read is kept (ended(),
// ended_in_suspicion()): a drive between two stops that still excluded the main belief when it
// ended, undecided, may have read another load (the pipeline then holds it until a later drive
// tells whether that load is gone).
//
// Pure: time comes from the samples. Not thread-safe; allocates nothing after construction.
#pragma once

#include <string>

#include "vmass/core/bayes_estimator.hpp"
#include "vmass/core/mass_prior.hpp"
#include "vmass/core/rls_estimator.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/core/supervisor.hpp"

namespace vmass {

struct LoadChangeParams {
  bool detect_in_motion = true;  ///< used only when the suspension does not read the load
  double min_stop_s = 5.0;       ///< a standstill this long may have changed the load
  double decide_sigma = 4.0;
  double min_change_fraction = 0.03;  ///< of the empty mass
  long min_pairs = 300;               ///< challenger pairs before it may decide
  /// Pairs per posterior update of a Bayes challenger (0: the estimator's bayes.batch_size).
  /// The suspicion can only be raised when the challenger's posterior moves: with the
  /// estimator's 100 pairs that is 25-40 s of driving after the stop on a car that gives 4 %
  /// of its ticks, all of them with the interval on the old load. Conjugacy makes the decision
  /// itself independent of the batch.
  int batch_size = 10;
  /// The challenger's own differencing (the tick rate is the estimator's); by default the
  /// belief's. In another band the two differ by what the model leaves out (the driveline mode
  /// grows with the band) and the challenger is suspected of a change that did not happen.
  double differencing_dt_s = 0.6;
  double filter_cutoff_hz = 0.7;
  /// The probability that a long stop changed the load, before the drive since says anything
  /// (load_change_odds.hpp): weighs the challenger against the belief once the challenger has
  /// its min_pairs and still neither decides nor agrees. In (0, 1).
  double change_prior = 0.5;

  std::string validate() const;
};

class LoadChangeMonitor {
 public:
  /// `start_prior`: where a challenger starts (the no-static prior); `use_rls`: the kind of
  /// the main regressor.
  LoadChangeMonitor(const LoadChangeParams& params, const RlsParams& rls, const BayesParams& bayes,
                    const SupervisorParams& supervisor, bool use_rls, const MassPrior& start_prior,
                    double empty_mass_kg, double standstill_speed_mps);

  /// Tracks standstills; a long one (re)starts the challenger when driving resumes. Returns
  /// true on the tick it (re)starts.
  bool step(const Sample& sample);
  /// One block's extraction from the challenger's extractors: while a challenger runs, its
  /// supervisor weighs the pair (if any) against the challenger's belief, or refuses it.
  void offer(Block block, const Extraction& extraction);
  /// True when the challenger now contradicts `main` (see the header); the caller then takes
  /// challenger() as its belief and calls dismiss().
  bool contradicts(const RegressorState& main) const;
  /// True when the challenger's 95 % interval excludes `main`'s mass (see the header): a change
  /// is likely but not yet decided.
  bool suspects(const RegressorState& main) const;
  /// True while a challenger runs without the min_pairs it needs to decide: the load may have
  /// changed at the last stop and the drive has not yet shown either way.
  bool undecided() const;
  /// True when the challenger the last restart ended had its min_pairs and still suspected
  /// `main` (the belief it was judged against): that drive ended in a lasting suspicion.
  bool ended_in_suspicion(const RegressorState& main) const;
  const RegressorState& ended() const { return ended_; }
  bool ended_active() const { return ended_active_; }
  /// `reading`'s 95 % interval excludes `belief`'s mass, by more than min_change_fraction.
  bool reads_apart(const RegressorState& reading, const RegressorState& belief) const;
  const MassRegressor& challenger() const;
  const RlsEstimator& challenger_rls() const { return rls_; }
  const BayesEstimator& challenger_bayes() const { return bayes_; }
  const MassPrior& start_prior() const { return start_prior_; }
  bool active() const { return active_; }
  /// The vehicle was switched off (a restored state): a challenger starts when it drives.
  void assume_long_stop() { long_stop_ = true; }
  void dismiss() { active_ = false; }

 private:
  MassRegressor& regressor();

  LoadChangeParams params_;
  RlsEstimator rls_;
  BayesEstimator bayes_;
  Supervisor supervisor_;
  bool use_rls_;
  MassPrior start_prior_;
  double empty_mass_kg_;
  double standstill_speed_mps_;
  bool standing_ = false;
  TimeUs standing_since_us_ = 0;
  bool long_stop_ = false;  ///< the current standstill lasted min_stop_s
  bool active_ = false;
  bool ended_active_ = false;  ///< a challenger ran until the last restart
  RegressorState ended_;       ///< its state then
};

}  // namespace vmass
