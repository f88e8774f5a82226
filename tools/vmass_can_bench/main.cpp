// vmass-can-bench: decoding throughput of the compiled DBC decoder against cantools.
//
//   vmass-can-bench [--dbc FILE] [--frames N] [--seed S] [--python PY] [--runs R]
//                   [Google Benchmark flags]
//
// Generates N random frames of the DBC's messages (uniform over messages, random payloads of the
// DBC length; messages with overlapping signals, which cantools cannot decode, are left out),
// times decoding them all (Google Benchmark, R repetitions, median), then has cantools decode
// the same frames (tools/vmass_can_bench/cantools_bench.py, median of R runs) and prints
// frames per second, ns per frame and the ratio. Both sides are timed in CPU time.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "vmass/can/candump.hpp"
#include "vmass/can/dbc.hpp"
#include "vmass/can/decoder.hpp"

namespace {

using namespace vmass::can;

std::vector<CanFrame> g_frames;
const Decoder* g_decoder = nullptr;
std::string g_log_text;

void BM_Decode(benchmark::State& state) {
  // The consumer stores each value by signal index, as a mapping layer would.
  std::vector<double> values(static_cast<std::size_t>(g_decoder->max_signals_per_message()));
  double* out = values.data();
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    for (const CanFrame& f : g_frames) {
      g_decoder->decode(f, [out](int i, double v) { out[i] = v; });
    }
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(g_frames.size()));
}

void BM_DecodeInto(benchmark::State& state) {
  std::vector<double> values(static_cast<std::size_t>(g_decoder->max_signals_per_message()));
  std::vector<std::uint8_t> present(values.size());
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    for (const CanFrame& f : g_frames) {
      g_decoder->decode_into(f, nullptr, values.data(), present.data());
    }
    benchmark::DoNotOptimize(values.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(g_frames.size()));
}

void BM_ParseCandumpLines(benchmark::State& state) {
  CandumpRecord rec;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    std::size_t begin = 0;
    while (begin < g_log_text.size()) {
      std::size_t end = g_log_text.find('\n', begin);
      if (end == std::string::npos) end = g_log_text.size();
      parse_candump_line(std::string_view(g_log_text).substr(begin, end - begin), &rec);
      benchmark::DoNotOptimize(rec.frame.id);
      begin = end + 1;
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(g_frames.size()));
}

/// Keeps the median aggregate of each benchmark (ns per iteration) while printing as usual.
class MedianReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.aggregate_name == "median") medians[r.run_name.function_name] = r.GetAdjustedCPUTime();
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> medians;  // in the run's time unit (ns)
};

std::string arg_value(int& argc, char** argv, const std::string& name, const std::string& def) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    std::string value;
    int used = 0;
    if (a == name && i + 1 < argc) {
      value = argv[i + 1];
      used = 2;
    } else if (a.rfind(name + "=", 0) == 0) {
      value = a.substr(name.size() + 1);
      used = 1;
    }
    if (used > 0) {
      for (int j = i; j + used < argc; ++j) argv[j] = argv[j + used];
      argc -= used;
      return value;
    }
  }
  return def;
}

}  // namespace

// Over 80 lines: a benchmark's setup and report, not product code.
// NOLINTNEXTLINE(readability-function-size)
int main(int argc, char** argv) {
  const std::string dbc = arg_value(argc, argv, "--dbc", VMASS_BENCH_DEFAULT_DBC);
  const int frame_count = std::atoi(arg_value(argc, argv, "--frames", "20000").c_str());
  const unsigned seed =
      static_cast<unsigned>(std::atoi(arg_value(argc, argv, "--seed", "1").c_str()));
  const std::string python = arg_value(argc, argv, "--python", VMASS_BENCH_PYTHON);
  const int runs = std::atoi(arg_value(argc, argv, "--runs", "7").c_str());
  const std::string script = VMASS_BENCH_SCRIPT;

  DbcParseResult parsed = load_dbc_file(dbc);
  std::vector<std::string> overlapping;
  for (const DbcDiagnostic& d : parsed.diagnostics) {
    const auto a = d.message.find(" of message ");
    const auto b = d.message.find(" overlaps ");
    if (a != std::string::npos && b != std::string::npos && b > a) {
      const std::string name = d.message.substr(a + 12, b - a - 12);
      if (std::find(overlapping.begin(), overlapping.end(), name) == overlapping.end()) {
        overlapping.push_back(name);
      }
    }
  }
  std::string error;
  auto decoder = Decoder::compile(parsed.database, &error);
  if (!decoder) {
    std::cerr << dbc << ": " << error << "\n";
    return 1;
  }
  g_decoder = &*decoder;
  std::vector<int> usable;
  for (int m = 0; m < decoder->message_count(); ++m) {
    const Message& msg = decoder->database().messages[static_cast<std::size_t>(m)];
    if (std::find(overlapping.begin(), overlapping.end(), msg.name) == overlapping.end()) {
      usable.push_back(m);
    }
  }
  std::mt19937_64 rng(seed);
  std::ostringstream log;
  CandumpWriter writer(log);
  std::size_t signals = 0;
  for (int i = 0; i < frame_count; ++i) {
    const Message& msg =
        decoder->database().messages[static_cast<std::size_t>(usable[rng() % usable.size()])];
    CanFrame f;
    f.time_us = 1700000000000000 + i;
    f.id = msg.id;
    f.flags = static_cast<std::uint8_t>((msg.extended ? kExtended : 0) | (msg.fd ? kFd : 0));
    f.len = static_cast<std::uint8_t>(msg.length);
    for (int b = 0; b < msg.length; ++b) f.data[b] = static_cast<std::uint8_t>(rng());
    g_frames.push_back(f);
    writer.write(f, "can0");
    decoder->decode(f, [&](int, double) { ++signals; });
  }
  g_log_text = log.str();
  std::printf(
      "vmass-can-bench: %s, %d frames of %zu messages (%zu left out: overlapping "
      "signals), %.1f signals per frame\n",
      dbc.c_str(), frame_count, usable.size(), overlapping.size(),
      static_cast<double>(signals) / frame_count);

  benchmark::Initialize(&argc, argv);
  const std::string reps = std::to_string(runs);
  for (auto* b : {benchmark::RegisterBenchmark("decode", BM_Decode),
                  benchmark::RegisterBenchmark("decode_into", BM_DecodeInto),
                  benchmark::RegisterBenchmark("parse_candump_line", BM_ParseCandumpLines)}) {
    b->Repetitions(runs)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);
  }
  MedianReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  if (reporter.medians.count("decode") == 0) {
    std::cerr << "vmass-can-bench: no median for decode (filtered out?)\n";
    return 1;
  }
  // CPU time (the machine may be shared), in the benchmark unit (us) per pass over all frames.
  const double ns_per_frame = reporter.medians["decode"] * 1000.0 / frame_count;
  std::printf("vmass decode: %.1f ns/frame, %.3g frames/s (median of %d runs)\n", ns_per_frame,
              1e9 / ns_per_frame, runs);

  const std::string log_path = "/tmp/vmass_can_bench_" + std::to_string(::getpid()) + ".log";
  {
    std::ofstream out(log_path);
    out << g_log_text;
  }
  const std::string cmd = python + " " + script + " --dbc " + dbc + " --log " + log_path +
                          " --runs " + std::to_string(runs);
  FILE* p = ::popen(cmd.c_str(), "r");
  std::string json;
  if (p != nullptr) {
    char buf[4096];
    while (std::fgets(buf, sizeof buf, p) != nullptr) json += buf;
    const int rc = ::pclose(p);
    if (rc != 0) json.clear();
  }
  std::remove(log_path.c_str());
  const auto key = json.find("\"ns_per_frame_median\": ");
  if (key == std::string::npos) {
    std::printf("cantools: not run (%s failed; run scripts/install-python-deps.sh)\n", cmd.c_str());
    return 1;
  }
  const double cantools_ns = std::atof(json.c_str() + key + 23);
  std::printf("cantools decode: %.1f ns/frame, %.3g frames/s (median of %d runs) %s", cantools_ns,
              1e9 / cantools_ns, runs, json.c_str());
  std::printf("ratio: vmass is %.0fx faster than cantools\n", cantools_ns / ns_per_frame);
  return 0;
}
