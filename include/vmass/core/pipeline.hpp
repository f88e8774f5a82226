// Pipeline: the whole estimator of the paper (Fig. 3) on a stream of Samples.
//
//   Sample -> StaticInitializer (eq. 3, load changes)    -> prior of the regressor
//          -> LongitudinalExtractor (eqs. 4-7, Table II)  -> Supervisor (eq. 13, innovation
//          -> LateralExtractor (eqs. 8-12, Table III)     -> gate) -> RlsEstimator | BayesEstimator
//          -> Estimate
//
// step() is called once per tick with the sample of that tick (time stamps increasing); it
// returns whether the published estimate changed and the per-block diagnostic records. Same
// sample sequence -> bit-identical estimates, in the daemon and offline.
//
// Pure: no threads, clocks, files or logging. Not thread-safe. Allocates only in the
// constructor.
#pragma once

#include <array>
#include <string>

#include "vmass/core/bayes_estimator.hpp"
#include "vmass/core/estimate.hpp"
#include "vmass/core/extraction.hpp"
#include "vmass/core/lateral_extractor.hpp"
#include "vmass/core/longitudinal_extractor.hpp"
#include "vmass/core/rls_estimator.hpp"
#include "vmass/core/static_initializer.hpp"
#include "vmass/core/supervisor.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass {

enum class RegressorType : std::uint8_t { kRls, kBayes };
std::string_view regressor_type_name(RegressorType t);

struct EstimatorParams {
  RegressorType type = RegressorType::kBayes;
  DifferencingParams differencing;
  StaticInitParams static_init;
  LongitudinalParams longitudinal;
  LateralParams lateral;
  SupervisorParams supervisor;
  RlsParams rls;
  BayesParams bayes;
  double converged_ci_halfwidth_fraction = 0.01;

  std::string validate() const;
};

struct PipelineParams {
  VehicleParams vehicle;
  SuspensionParams suspension;
  EstimatorParams estimator;

  std::string validate() const;
};

struct StepResult {
  bool estimate_changed = false;
  bool reinitialised = false;  ///< a (new) static prior restarted the regressor this tick
  std::array<PairEvent, kBlockCount> events{};
};

class Pipeline {
 public:
  /// params must be valid (validate() == "").
  explicit Pipeline(const PipelineParams& params);
  Pipeline(const Pipeline&) = delete;  // holds a pointer to its own active regressor
  Pipeline& operator=(const Pipeline&) = delete;

  StepResult step(const Sample& sample);
  const Estimate& estimate() const { return estimate_; }
  const MassRegressor& regressor() const { return *regressor_; }
  const PipelineParams& params() const { return params_; }

 private:
  void restart(const MassPrior& prior, StatusReason reason);
  void refresh_estimate(const Sample& sample);

  PipelineParams params_;
  StaticInitializer static_init_;
  LongitudinalExtractor longitudinal_;
  LateralExtractor lateral_;
  Supervisor supervisor_;
  RlsEstimator rls_;
  BayesEstimator bayes_;
  MassRegressor* regressor_;
  bool has_prior_ = false;
  StatusReason prior_reason_ = StatusReason::kWaitingForStandstill;
  Estimate estimate_;
};

}  // namespace vmass
