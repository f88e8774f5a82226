// vmass-bench: the micro-benchmarks of docs/performance.md (Google Benchmark): frame decoding on
// a production DBC in vmass-can's path and the daemon's, candump parsing, a pipeline tick, an
// RLS update, a Bayes batch, the estimate CSV's number formatting.
//
//   vmass-bench [--dbc FILE] [--inputs YAML] [--frames N] [--seed S] [--config FILE]
//               [--samples CSV] [--frames-log PATH] [Google Benchmark flags]
//
// --dbc (default tests/data/dbc/vw_mqb.dbc) with the input mapping --inputs (a `can.inputs`
// block; default vw_mqb_inputs.yaml beside this file) gives N random frames (seed S; see
// bench_frames.hpp); --frames-log writes them as a candump -l log for cantools_bench.py (the
// ratio of docs/performance.md). --config and --samples (default: the golden paper_exp2 drive)
// feed the pipeline tick. --version prints the name and version; --help our options, then
// Google Benchmark's. Exit codes: 0 ok, 2 a usage error (an option neither takes, a bad value)
// or an input that cannot be read.
#include <benchmark/benchmark.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include <yaml-cpp/yaml.h>

#include "core_benchmarks.hpp"
#include "decode_benchmarks.hpp"
#include "format_benchmarks.hpp"
#include "vmass/config/config.hpp"
#include "vmass/csv/samples_csv.hpp"
#include "vmass/version.hpp"

namespace {

using namespace vmass;

struct Options {
  std::string dbc = VMASS_BENCH_DBC;
  std::string inputs = VMASS_BENCH_INPUTS;
  std::string config = VMASS_BENCH_CONFIG;
  std::string samples = VMASS_BENCH_SAMPLES;
  std::string frames_log;
  int frames = 20'000;
  unsigned seed = 1;
};

/// Takes `--name VALUE` or `--name=VALUE` out of argv (the rest goes to Google Benchmark).
std::optional<std::string> take_option(int& argc, char** argv, const std::string& name) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    int used = 0;
    std::string value;
    if (a == name && i + 1 < argc) {
      value = argv[i + 1];
      used = 2;
    } else if (a.rfind(name + "=", 0) == 0) {
      value = a.substr(name.size() + 1);
      used = 1;
    } else {
      continue;
    }
    for (int j = i; j + used < argc; ++j) argv[j] = argv[j + used];
    argc -= used;
    return value;
  }
  return std::nullopt;
}

/// `text` as a whole number in [low, high], or nullopt.
std::optional<long> whole_number(const std::string& text, long low, long high) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || v < low || v > high) return std::nullopt;
  return v;
}

/// Our options out of argv; "" or why they are wrong.
std::string parse_options(int& argc, char** argv, Options* o) {
  for (auto [name, field] : {std::pair{"--dbc", &o->dbc},
                             {"--inputs", &o->inputs},
                             {"--config", &o->config},
                             {"--samples", &o->samples},
                             {"--frames-log", &o->frames_log}}) {
    if (auto v = take_option(argc, argv, name)) *field = *v;
  }
  if (auto v = take_option(argc, argv, "--frames")) {
    const auto n = whole_number(*v, 1, 100'000'000);
    if (!n) return "--frames " + *v + ": not a whole number in [1, 100000000]";
    o->frames = static_cast<int>(*n);
  }
  if (auto v = take_option(argc, argv, "--seed")) {
    const auto n = whole_number(*v, 0, 4'294'967'295);
    if (!n) return "--seed " + *v + ": not a whole number in [0, 4294967295]";
    o->seed = static_cast<unsigned>(*n);
  }
  return "";
}

constexpr const char* kUsage =
    "Usage: vmass-bench [OPTIONS] [Google Benchmark flags]\n"
    "vmass-bench: the micro-benchmarks of docs/performance.md (Google Benchmark)\n\n"
    "Options:\n"
    "  --dbc FILE          the DBC whose frames are decoded (default tests/data/dbc/vw_mqb.dbc)\n"
    "  --inputs YAML       its can.inputs mapping (default vw_mqb_inputs.yaml)\n"
    "  --frames N          random frames to decode (default 20000)\n"
    "  --seed S            their seed (default 1)\n"
    "  --config FILE       the config of the pipeline tick (default: the golden paper_exp2)\n"
    "  --samples CSV       the drive it ticks on (default: the golden paper_exp2)\n"
    "  --frames-log PATH   also write the frames as a candump -l log (cantools_bench.py)\n"
    "  --version           print the program's name and version, then exit\n"
    "  --help              print this help, then Google Benchmark's, and exit\n\n";

/// --help, --version and every option: nullopt to go on, else the exit code. What is left of
/// argv after our options goes to Google Benchmark, which must know all of it.
std::optional<int> parse_command_line(int& argc, char** argv, Options* o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--version") {
      std::cout << "vmass-bench " << vmass::kVersion << "\n";
      return 0;
    }
    if (a == "--help" || a == "-h") {
      std::cout << kUsage << std::flush;
      char help[] = "--help";
      char* args[] = {argv[0], help, nullptr};
      int n = 2;
      benchmark::Initialize(&n, args);  // prints Google Benchmark's flags and exits 0
      return 0;
    }
  }
  if (const std::string error = parse_options(argc, argv, o); !error.empty()) {
    std::cerr << "vmass-bench: " << error << "\n";
    return 2;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
    std::cerr << "vmass-bench: --help lists the options\n";
    return 2;
  }
  return std::nullopt;
}

/// The DBC, its frames and the mapping onto it; "" or why not.
std::string load_decode_data(const Options& o, bench::DecodeBenchData* data) {
  const can::DbcParseResult parsed = can::load_dbc_file(o.dbc);
  std::string error;
  auto decoder = can::Decoder::compile(parsed.database, &error);
  if (!decoder) return o.dbc + ": " + error;
  data->decoder = std::make_shared<const can::Decoder>(std::move(*decoder));
  try {
    const YAML::Node inputs = YAML::LoadFile(o.inputs)["inputs"];
    error = signals::parse_signal_mapping(inputs, o.inputs, *data->decoder, o.dbc, &data->mapping);
  } catch (const YAML::Exception& e) {
    error = o.inputs + ": " + e.what();
  }
  if (!error.empty()) return error;
  data->frames =
      bench::random_frames(*data->decoder, bench::overlapping_messages(parsed), o.frames, o.seed);
  std::vector<bool> mapped(static_cast<std::size_t>(data->decoder->message_count()), false);
  for (const signals::InputMapping& m : data->mapping.inputs) {
    for (const signals::MappedSignal& s : m.terms)
      mapped[static_cast<std::size_t>(s.ref.message)] = true;
  }
  data->mapped_frames = bench::frames_of(*data->decoder, data->frames.frames, mapped);
  return "";
}

/// The drive the pipeline ticks on; "" or why not.
std::string load_core_data(const Options& o, bench::CoreBenchData* data) {
  const ConfigLoad config = load_config(o.config);
  if (!config.ok()) return config.error;
  data->params = config.config->pipeline;
  SamplesCsvReader reader(o.samples);
  if (!reader.error().empty()) return reader.error();
  while (std::optional<Sample> s = reader.next()) data->samples.push_back(*s);
  data->pairs = bench::synthetic_pairs(10'000, o.seed);
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto code = parse_command_line(argc, argv, &o)) return *code;
  bench::DecodeBenchData decode;
  bench::CoreBenchData core;
  std::string error = load_decode_data(o, &decode);
  if (error.empty()) error = load_core_data(o, &core);
  if (!error.empty()) {
    std::cerr << "vmass-bench: " << error << "\n";
    return 2;
  }
  if (!o.frames_log.empty()) std::ofstream(o.frames_log) << decode.frames.candump_text;
  std::cout << "vmass-bench: " << o.dbc << ": " << decode.frames.frames.size() << " frames of "
            << decode.frames.messages_used << " messages (" << decode.frames.messages_left_out
            << " left out: overlapping signals), " << decode.frames.signals_per_frame
            << " signals per frame, " << decode.mapped_frames.size() << " of mapped messages\n";
  bench::register_decode_benchmarks(decode);
  bench::register_core_benchmarks(core);
  bench::register_format_benchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
