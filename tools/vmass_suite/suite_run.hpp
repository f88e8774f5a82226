// One run of the accuracy suite: one population vehicle on one scenario with one seed, under
// one realism, scored for each knowledge (known scale, datasheet scale) and each estimator
// (vmass rls and bayes on their defaults, and the baselines), all on the same frames.
//
// The path is the product's: the vehicle's DBC and the config its engineer writes go to a
// work directory and are loaded with the real loaders (load_config, load_can_inputs); the bus
// is turned into candump text and read back by CandumpReader and the runtime's tick driver, exactly
// as `vmass-replay --log` does; the Pipeline steps on those samples. A config the loader refuses
// (an input or section the estimator does not support yet) makes the run "unsupported" for
// vmass with the loader's message; the baselines are scored only where the config loads (they
// read the same decoded samples).
//
// Thread-safe for distinct work directories.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vmass/core/pipeline.hpp"
#include "vmass/scoring/accuracy_metrics.hpp"
#include "vmass/scoring/verdict_tally.hpp"
#include "vmass/sim/datasheet_config.hpp"
#include "vmass/sim/realism.hpp"
#include "vmass/sim/simulator.hpp"
#include "vmass/sim/torque_signal_variant.hpp"

namespace vmass::suite {

using scoring::AccuracyResult;
using scoring::Truth;

struct RunSpec {
  std::string vehicle_id;  ///< "<class>-<seed>"
  std::string scenario;
  std::uint64_t seed = 1;
  sim::Realism realism = sim::Realism::all();
  std::string realism_label = "all";  ///< for the output (e.g. "only:driveline_mode")
  std::vector<sim::Knowledge> knowledge = {sim::Knowledge::kKnownScale,
                                           sim::Knowledge::kDatasheetScale};
  std::vector<std::string> estimators;  ///< rls, bayes, and baseline names
  std::string estimator_yaml;           ///< appended to every config (experiments)
  std::string series_dir;               ///< "": no per-tick series; else CSVs go there
  /// The torque signal every vehicle has (torque_signal_variant.hpp; --torque-signal).
  sim::TorqueSignalVariant torque_signal = sim::TorqueSignalVariant::kAsDrawn;
};

struct EstimatorResult {
  std::string estimator;
  sim::Knowledge knowledge = sim::Knowledge::kKnownScale;
  bool supported = true;
  std::string unsupported_reason;
  AccuracyResult accuracy;
  double availability_longitudinal = AccuracyResult::kNaN;
  double availability_lateral = AccuracyResult::kNaN;
  long accepted_longitudinal = 0, accepted_lateral = 0;
  long pairs_used = 0;
  std::string status_end, reason_end;
  double initial_mass_kg = AccuracyResult::kNaN;   ///< vmass: the last prior (static or empty)
  double identified_lag_s = AccuracyResult::kNaN;  ///< vmass: the longitudinal block's lag
  double accel_noise_mps2 = AccuracyResult::kNaN;  ///< vmass: its measured noise
  /// vmass: what the rotating term read at the end ("wheel_speed" or "accelerometer"), and the
  /// speed signal's mean interval between changes (SpeedRefresh; NaN before a change).
  std::string rotating_accel;
  double speed_refresh_s = AccuracyResult::kNaN;
  /// vmass: the pair-term fit's rotating-mass error c_rot and its std at the end (NaN: the fit
  /// did not apply), and the mass shift it made, kg.
  double rotating_error = AccuracyResult::kNaN;
  double rotating_error_std = AccuracyResult::kNaN;
  double pair_term_shift_kg = AccuracyResult::kNaN;
  scoring::VerdictTally verdicts;  ///< vmass: every block's verdict at every tick (why no pair)
};

struct RunResult {
  RunSpec spec;
  std::string vehicle_class;
  std::string error;  ///< the run itself failed (a bug): every result is missing
  double duration_s = 0.0;
  double initial_true_mass_kg = 0.0;
  /// Seconds of the drive with |dv/dt| > 0.3 m/s^2 above 2 m/s (the truth): a drive with 5 s
  /// of it must give every estimator pairs (issue 29).
  double excited_s = 0.0;
  /// The truth of what the pair-term fit reads: the true rotating masses are (1 + this) times
  /// the configured ones (0 without the datasheet_errors effect).
  double true_rotating_error = 0.0;
  std::vector<EstimatorResult> results;
};

/// The simulation's truth (mass and speed), its times shifted by `time_offset_us` (as the
/// drive's frames).
Truth truth_track(const sim::SimulationResult& result, TimeUs time_offset_us);

/// Steps `pipeline` (new, or restored from a state) through the samples and scores it.
EstimatorResult run_pipeline(const std::string& name, Pipeline& pipeline,
                             const std::vector<Sample>& samples, const Truth& truth,
                             const std::string& series_path);

/// The estimators run by default: rls, bayes, then every baseline.
std::vector<std::string> default_estimators();

RunResult run_suite_case(const RunSpec& spec, const std::string& work_dir);

/// One JSON object per estimator result, one per line.
std::string to_json_lines(const RunResult& run);

}  // namespace vmass::suite
