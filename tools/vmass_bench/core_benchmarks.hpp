// Estimator benchmarks (Google Benchmark) through the core's public API, per item:
//   core/pipeline_tick   Pipeline::step on a drive's samples (every block, gate and regressor
//                        of a real tick; a fresh Pipeline per pass over the drive, untimed)
//   core/rls_update      RlsEstimator::update of one accepted pair
//   core/bayes_batch     BayesEstimator::update of a whole batch (batch_size pairs, the
//                        posterior update at its end included): items are batches
// The pairs are synthetic (y = M da + mu + noise, seeded). CPU time.
#pragma once

#include <vector>

#include "vmass/core/pipeline.hpp"

namespace vmass::bench {

struct CoreBenchData {
  PipelineParams params;
  std::vector<Sample> samples;        ///< a drive, in time order
  std::vector<RegressionPair> pairs;  ///< accepted pairs, in time order
};

/// `count` pairs of a 1659 kg car, mu 50 N, noise 100 N, from seed.
std::vector<RegressionPair> synthetic_pairs(int count, unsigned seed);

/// Registers the benchmarks above over `data`, which must outlive them.
void register_core_benchmarks(const CoreBenchData& data);

}  // namespace vmass::bench
