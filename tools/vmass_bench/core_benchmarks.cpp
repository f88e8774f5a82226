#include "core_benchmarks.hpp"

#include <benchmark/benchmark.h>

#include <optional>
#include <random>

namespace vmass::bench {
namespace {

constexpr MassPrior kPrior{1648.0, 100.0, 0.0, 200.0};

void pipeline_tick(benchmark::State& state, const CoreBenchData& data) {
  std::optional<Pipeline> pipeline;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    state.PauseTiming();
    pipeline.emplace(data.params);
    state.ResumeTiming();
    for (const Sample& s : data.samples) benchmark::DoNotOptimize(pipeline->step(s));
  }
  benchmark::DoNotOptimize(pipeline->estimate().mass_kg);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(data.samples.size()));
}

void rls_update(benchmark::State& state, const CoreBenchData& data) {
  RlsEstimator rls(data.params.estimator.rls);
  rls.reset(kPrior);
  std::size_t i = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    benchmark::DoNotOptimize(rls.update(data.pairs[i]));
    if (++i == data.pairs.size()) i = 0;
  }
  benchmark::DoNotOptimize(rls.state().mass_kg);
  state.SetItemsProcessed(state.iterations());
}

void bayes_batch(benchmark::State& state, const CoreBenchData& data) {
  const BayesParams& params = data.params.estimator.bayes;
  BayesEstimator bayes(params);
  bayes.reset(kPrior);
  const auto batch = static_cast<std::size_t>(params.batch_size);
  std::size_t i = 0;
  std::int64_t batches = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    for (std::size_t k = 0; k < batch; ++k) {
      batches += bayes.update(data.pairs[i]) ? 1 : 0;
      if (++i == data.pairs.size()) i = 0;
    }
  }
  benchmark::DoNotOptimize(bayes.state().mass_kg);
  state.SetItemsProcessed(batches);
  state.SetLabel("batch of " + std::to_string(batch) + " pairs");
}

}  // namespace

std::vector<RegressionPair> synthetic_pairs(int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> delta_accel(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 100.0);
  std::vector<RegressionPair> pairs(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    RegressionPair& p = pairs[static_cast<std::size_t>(i)];
    p.time_us = static_cast<TimeUs>(i) * 10'000;
    p.delta_accel_mps2 = delta_accel(rng);
    p.y_n = 1659.0 * p.delta_accel_mps2 + 50.0 + noise(rng);
  }
  return pairs;
}

void register_core_benchmarks(const CoreBenchData& data) {
  const CoreBenchData* d = &data;
  benchmark::RegisterBenchmark("core/pipeline_tick",
                               [d](benchmark::State& s) { pipeline_tick(s, *d); });
  benchmark::RegisterBenchmark("core/rls_update", [d](benchmark::State& s) { rls_update(s, *d); });
  benchmark::RegisterBenchmark("core/bayes_batch",
                               [d](benchmark::State& s) { bayes_batch(s, *d); });
}

}  // namespace vmass::bench
