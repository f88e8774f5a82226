#include "format_benchmarks.hpp"

#include <benchmark/benchmark.h>

#include <charconv>
#include <cstdio>
#include <random>
#include <vector>

#include "vmass/csv/estimate_csv.hpp"
#include "vmass/csv/fixed_decimal.hpp"

namespace vmass::bench {
namespace {

std::vector<double> masses() {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> mass(-5000.0, 5000.0);
  std::vector<double> v(4096);
  for (double& x : v) x = mass(rng);
  return v;
}

/// Formats every mass with `format(buf, end, value)` per pass.
template <class Format>
void format_masses(benchmark::State& state, Format format) {
  const std::vector<double> values = masses();
  char buf[kMaxFixedChars];
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    for (const double v : values) benchmark::DoNotOptimize(format(buf, buf + sizeof buf, v));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(values.size()));
}

void estimate_row(benchmark::State& state) {
  const std::vector<double> values = masses();
  Estimate e;
  e.mass_known = true;
  e.blocks[0] = {36'000, 9'000, 4'000, 12};
  e.blocks[1] = {36'000, 7'000, 3'000, 5};
  std::vector<char> row(EstimateCsvWriter::kMaxRowChars);
  std::size_t i = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    e.time_us += 10'000;
    e.mass_kg = 1659.0 + values[i];
    e.ci_low_kg = e.mass_kg - 17.3;
    e.ci_high_kg = e.mass_kg + 17.3;
    e.mu_n = values[(i + 1) % values.size()] * 0.01;
    e.mass_std_kg = 8.8;
    e.initial_mass_kg = 1648.0;
    benchmark::DoNotOptimize(EstimateCsvWriter::format_row(e, row.data()));
    i = (i + 1) % values.size();
  }
  state.SetItemsProcessed(state.iterations());
}

}  // namespace

void register_format_benchmarks() {
  benchmark::RegisterBenchmark("csv/estimate_row", estimate_row);
  benchmark::RegisterBenchmark("format/printf_fixed", [](benchmark::State& s) {
    format_masses(s, [](char* b, char* end, double v) {
      return std::snprintf(b, static_cast<std::size_t>(end - b), "%.3f", v);
    });
  });
  benchmark::RegisterBenchmark("format/to_chars_fixed", [](benchmark::State& s) {
    format_masses(s, [](char* b, char* end, double v) {
      return std::to_chars(b, end, v, std::chars_format::fixed, 3).ptr;
    });
  });
  benchmark::RegisterBenchmark("format/write_fixed", [](benchmark::State& s) {
    format_masses(s, [](char* b, char* end, double v) { return write_fixed(b, end, v, 3); });
  });
}

}  // namespace vmass::bench
