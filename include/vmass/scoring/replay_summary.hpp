// ReplaySummary: what vmass-replay reports about a run, and how good it was against a truth
// (truth.hpp). Its text, table and JSON, is replay_summary_text.hpp.
//
// Metrics (per run): final mass and error (tick_comparison.hpp); the time within 5%, 2% and 1%
// of the truth, measured from the first tick (see Result); the coverage of dynamic ticks (the
// fraction of ticks with a dynamic estimate, one that used a pair, whose 95% interval contains
// the truth); the prior and where it came from; pairs used in the estimate and accepted by the
// supervisor, apart (Bayes holds a batch back until it completes or is flushed); availability
// per block, and each block's verdicts (why it took no pair); status at the end. The accuracy suite
// scores differently (accuracy_metrics.hpp). Not thread-safe.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "vmass/core/estimate.hpp"
#include "vmass/core/pipeline.hpp"
#include "vmass/scoring/truth.hpp"
#include "vmass/scoring/verdict_tally.hpp"
#include "vmass/scoring/within_tracker.hpp"

namespace vmass::scoring {

/// The replay's tolerances, as fractions of the truth: 5, 2, 1 %.
constexpr Tolerances kReplayTolerances = {0.05, 0.02, 0.01};

class ReplaySummary {
 public:
  explicit ReplaySummary(std::optional<Truth> truth) : truth_(std::move(truth)) {}

  /// The estimate of each tick, in order.
  void add(const Estimate& estimate);
  /// The same tick's outcome of each block (why a pair was or was not taken).
  void add_events(const std::array<PairEvent, kBlockCount>& events) { verdicts_.add(events); }
  /// The estimate after Pipeline::flush() at the end of the input (same time as the last tick,
  /// the open Bayes batch taken in): it becomes the final estimate; no tick is counted.
  void finish(const Estimate& flushed);

  struct Result {
    bool has_estimate = false;
    Estimate final_estimate;
    long pairs_accepted = 0;  ///< by the supervisor, both blocks (pairs_used: in the estimate)
    std::optional<double> true_mass_kg;
    std::optional<double> error_percent;  ///< (estimate - truth) / truth
    /// Per kReplayTolerances: the time from the FIRST TICK after which every estimate stays
    /// within the tolerance to the end (from the first estimate when none was ever outside).
    /// Empty when the final estimate is outside, and when it used no pair (a prior proves
    /// nothing). Ticks without an estimate are not counted.
    std::array<std::optional<double>, kToleranceCount> time_within_since_first_tick_s;
    /// Among the ticks whose estimate used a pair, the share whose interval covers the truth.
    std::optional<double> coverage_of_dynamic_ticks;
    double duration_s = 0.0;
    long ticks = 0;
    long reinitialisations = 0;
    VerdictTally verdicts;  ///< every block's verdict at every tick (add_events)
    /// What is learnt about the car after this drive (Pipeline::learnt_scale_if_ended()): set
    /// by set_learnt() when the run declared a known mass, restored something learnt or had a
    /// standstill reading of its load that its pairs could anchor the scale on.
    struct Learnt {
      double scale = 1.0;
      double relative_std = 0.0;
      long evidence = 0;
      long changes = 0;
      long anchors = 0;      ///< drives whose standstill reading anchored it (StaticAnchor)
      int known_masses = 0;  ///< declared during the run
      /// The learnt gear masses (Pipeline::gear_masses_if_ended()): drives of evidence, and
      /// per gear (index gear - 1) the correction of its rotating mass and its std, kg.
      long gear_drives = 0;
      std::vector<double> gear_correction_kg;
      std::vector<double> gear_std_kg;
    };
    std::optional<Learnt> learnt;
    /// The speed signal was found too coarse for its derivative (SpeedRefresh): its mean
    /// interval between changes, s; the rotating term read the accelerometer instead.
    std::optional<double> coarse_speed_interval_s;
    /// The drive's fit of the configured rotating masses' and converter map's errors
    /// (Pipeline::pair_term_fit()) at its end, when it applied.
    std::optional<PairTermFit> pair_terms;
  };
  Result result() const;
  void set_learnt(const Result::Learnt& learnt) { learnt_ = learnt; }
  void set_pair_terms(const PairTermFit& fit) { pair_terms_ = fit; }
  void set_coarse_speed(double interval_s) { coarse_speed_interval_s_ = interval_s; }

 private:
  void check_tolerances(const Estimate& e);
  void time_within(Result* r) const;

  std::optional<Truth> truth_;
  TimeUs first_us_ = 0;
  bool started_ = false;
  Estimate last_;
  bool has_last_ = false;
  long ticks_ = 0;
  long reinitialisations_ = 0;
  long dynamic_ticks_ = 0;
  long covered_ticks_ = 0;
  WithinTracker within_{kReplayTolerances};
  VerdictTally verdicts_;
  std::optional<Result::Learnt> learnt_;
  std::optional<double> coarse_speed_interval_s_;
  std::optional<PairTermFit> pair_terms_;
  bool any_mass_ = false;
  TimeUs first_mass_us_ = 0;
};

/// What the drive leaves learnt about the car (Pipeline::learnt_scale_if_ended(),
/// gear_masses_if_ended()) into `summary`, when a known mass was declared (`known_masses`) or
/// anything is learnt: vmass-replay and the Python binding report the same.
void record_learnt(const Pipeline& pipeline, int known_masses, ReplaySummary* summary);
/// Whether the drive found its speed signal too coarse for the rotating term (SpeedRefresh)
/// into `summary`: vmass-replay and the Python binding report the same.
void record_speed_signal(const Pipeline& pipeline, ReplaySummary* summary);
/// The drive's pair-term fit (Pipeline::pair_term_fit()), when it applies, into `summary`.
void record_pair_terms(const Pipeline& pipeline, ReplaySummary* summary);

}  // namespace vmass::scoring
