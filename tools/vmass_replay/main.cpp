// vmass-replay: drive the estimation pipeline offline over recorded samples or a CAN log, at
// the configured tick rate, and report how it did.
//
//   vmass-replay --config FILE (--samples CSV | --log LOG) [--truth CSV]
//                [--estimator rls|bayes] [--out CSV] [--plot PNG] [--json]
//
// --samples: samples.csv rows through a TickResampler (zero-order hold, stale after 5 ticks).
// --log: a candump -l log decoded with the config's `can:` section (DBC + signal mapping) into a
// SignalTable; tick k is at t0 + k / tick_rate_hz in log time (t0: the first frame's time), and
// its Sample is SignalTable::sample_at(tick time) after every frame stamped at or before it
// (the daemon's log replay does the same). Corrupt log lines are reported and counted, never
// fatal. --truth is read only when given, and refused (exit 2) when its time base is not the
// input's (Truth::check_time_base). At the end the open Bayes batch is flushed into the final
// estimate the summary prints. Exit codes: 0 ok, 1 write or plot failure, 2 usage, config or
// input error.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "exit_code.hpp"

#include "replay_summary.hpp"
#include "vmass/can/candump.hpp"
#include "vmass/config/config.hpp"
#include "vmass/core/pipeline.hpp"
#include "vmass/csv/estimate_csv.hpp"
#include "vmass/csv/samples_csv.hpp"
#include "vmass/csv/tick_resampler.hpp"
#include "vmass/signals/log_replay.hpp"
#include "vmass/signals/signal_table.hpp"

namespace fs = std::filesystem;

namespace {

// The plotting script ships beside our executables (build/bin or the install's bin).
std::string sibling_program(const std::string& name) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path candidate = self.parent_path() / name;
    if (fs::exists(candidate)) return candidate.string();
  }
  return name;  // rely on PATH
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Feeds the samples CSV through the tick resampler. False (and a message) on a bad file.
bool replay_samples(const std::string& path, const vmass::PipelineParams& params,
                    const std::function<void(const vmass::Sample&)>& on_tick) {
  vmass::SamplesCsvReader reader(path);
  if (!reader.error().empty()) {
    std::cerr << "vmass-replay: " << reader.error() << "\n";
    return false;
  }
  // A held sample older than 5 ticks is stale (a gap in the recording).
  vmass::TickResampler ticks(params.estimator.differencing.tick_rate_hz,
                             5.0 / params.estimator.differencing.tick_rate_hz);
  while (auto sample = reader.next()) ticks.push(*sample, on_tick);
  for (const auto& w : reader.warnings()) std::cerr << "vmass-replay: warning: " << w << "\n";
  if (reader.skipped_rows() > 0) {
    std::cerr << "vmass-replay: skipped " << reader.skipped_rows() << " malformed rows\n";
  }
  return true;
}

// Decodes the candump log into a SignalTable and ticks in log time (see the header comment).
bool replay_log(const std::string& path, const vmass::Config& config, double tick_rate_hz,
                const std::function<void(const vmass::Sample&)>& on_tick) {
  vmass::signals::CanInputsLoad can = vmass::signals::load_can_inputs(config);
  if (!can.ok()) {
    std::cerr << "vmass-replay: " << can.error << "\n";
    return false;
  }
  for (const std::string& w : can.inputs->warnings) std::cerr << "vmass-replay: " << w << "\n";
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::cerr << "vmass-replay: " << path << ": cannot open the log\n";
    return false;
  }
  vmass::signals::SignalTable table(can.inputs->decoder, can.inputs->mapping);
  vmass::can::CandumpReader reader(in, path);
  constexpr std::uint64_t kReportedLines = 10;
  reader.on_error([&](const vmass::can::CandumpError& e) {
    if (reader.stats().corrupt <= kReportedLines) {
      std::cerr << "vmass-replay: " << e.message << " (line skipped)\n";  // "path:line: ..."
    }
  });

  const vmass::signals::LogReplayStats replayed =
      vmass::signals::replay_candump(reader, table, tick_rate_hz, on_tick);

  const vmass::can::CandumpStats& ls = reader.stats();
  const vmass::signals::SignalTableCounters& c = table.counters();
  std::cerr << "vmass-replay: " << path << ": " << ls.frames << " frames, " << ls.corrupt
            << " corrupt lines; decoded " << c.decoded << ", unknown id " << c.unknown_id
            << ", too short " << c.malformed << ", error frames " << c.error_frames << "\n";
  std::string stale;
  for (int i = 0; i < vmass::kInputCount; ++i) {
    const auto& ic = c.inputs[static_cast<std::size_t>(i)];
    if (ic.stale > 0 || ic.invalid_values > 0) {
      stale += " " + std::string(vmass::input_name(static_cast<vmass::Input>(i))) + " (" +
               std::to_string(ic.stale) + " stale, " + std::to_string(ic.invalid_values) +
               " invalid)";
    }
  }
  if (!stale.empty()) std::cerr << "vmass-replay: inputs:" << stale << "\n";
  if (!replayed.any_frame) std::cerr << "vmass-replay: " << path << ": no frames\n";
  return true;
}

}  // namespace

// NOLINTNEXTLINE(readability-function-size): not split yet (issue 9)
int main(int argc, char** argv) {
  CLI::App app{"vmass-replay: run the mass estimator offline over recorded samples or a CAN log"};
  std::string config_path, samples_path, log_path, truth_path, out_path, plot_path, estimator;
  bool json = false;
  app.add_option("--config", config_path, "vmass YAML config")->required();
  auto* samples_opt = app.add_option("--samples", samples_path, "samples CSV (docs/formats.md)");
  auto* log_opt =
      app.add_option("--log", log_path, "candump -l log, decoded with the config's can: section");
  samples_opt->excludes(log_opt);
  log_opt->excludes(samples_opt);
  app.add_option("--truth", truth_path,
                 "truth CSV (time_s,mass_kg) in the input's time base; none by default");
  app.add_option("--estimator", estimator, "override estimator.type")
      ->check(CLI::IsMember({"rls", "bayes"}));
  app.add_option("--out", out_path, "write the estimate at every tick as CSV");
  app.add_option("--plot", plot_path, "write a PNG plot (needs --out or uses a temporary CSV)");
  app.add_flag("--json", json, "print the summary as one JSON object instead of a table");
  if (const auto code = vmass::tools::parse_command_line(app, argc, argv)) return *code;
  if (samples_path.empty() && log_path.empty()) {
    std::cerr << "vmass-replay: give the input: --samples CSV or --log LOG\n";
    return 2;
  }
  const std::string input_path = log_path.empty() ? samples_path : log_path;

  vmass::ConfigLoad loaded = vmass::load_config(config_path);
  if (!loaded.ok()) {
    std::cerr << "vmass-replay: " << loaded.error << "\n";
    return 2;
  }
  vmass::PipelineParams params = loaded.config->pipeline;
  if (!estimator.empty()) {
    params.estimator.type =
        estimator == "rls" ? vmass::RegressorType::kRls : vmass::RegressorType::kBayes;
  }

  std::optional<vmass::Truth> truth;
  if (!truth_path.empty()) {
    std::string error;
    truth = vmass::Truth::load(truth_path, &error);
    if (!truth) {
      std::cerr << "vmass-replay: " << error << "\n";
      return 2;
    }
  }

  std::string csv_path = out_path;
  if (csv_path.empty() && !plot_path.empty()) {
    csv_path = (fs::temp_directory_path() / ("vmass-replay-" + std::to_string(::getpid()) + ".csv"))
                   .string();
  }
  std::unique_ptr<vmass::EstimateCsvWriter> writer;
  if (!csv_path.empty()) {
    writer = std::make_unique<vmass::EstimateCsvWriter>(csv_path);
    if (!writer->ok()) {
      std::cerr << "vmass-replay: " << csv_path << ": cannot write\n";
      return 2;
    }
  }

  auto pipeline = std::make_unique<vmass::Pipeline>(params);
  vmass::ReplaySummary summary(truth);
  const vmass::TimeUs tick_period_us =
      vmass::from_seconds(1.0 / params.estimator.differencing.tick_rate_hz);
  std::string truth_refusal;  // the truth's time base is not the input's (checked at tick 0)
  bool first_tick = true;
  auto on_tick = [&](const vmass::Sample& sample) {
    if (first_tick && truth) truth_refusal = truth->check_time_base(sample.time_us, tick_period_us);
    first_tick = false;
    if (!truth_refusal.empty()) return;
    pipeline->step(sample);
    summary.add(pipeline->estimate());
    if (writer) writer->write(pipeline->estimate());
  };
  const bool read_ok = log_path.empty()
                           ? replay_samples(samples_path, params, on_tick)
                           : replay_log(log_path, *loaded.config,
                                        params.estimator.differencing.tick_rate_hz, on_tick);
  if (!truth_refusal.empty()) {
    std::cerr << "vmass-replay: " << truth_path << ": not the truth of " << input_path << ": "
              << truth_refusal << "\n";
  }
  if (!read_ok || !truth_refusal.empty()) {
    if (writer) writer->close();
    if (!csv_path.empty()) fs::remove(csv_path);  // nothing of this run is worth keeping
    return 2;
  }
  // The end of the input: the open Bayes batch enters the final estimate (the CSV keeps one
  // row per tick; the summary reports the flushed estimate).
  if (pipeline->flush()) summary.finish(pipeline->estimate());
  if (writer && !writer->close()) {
    std::cerr << "vmass-replay: " << csv_path << ": write failed\n";
    return 1;
  }
  const std::string name(pipeline->regressor().name());
  std::cout << (json ? summary.json(name) + "\n" : summary.table(name));

  if (!plot_path.empty()) {
    std::string command = shell_quote(sibling_program("vmass-plot")) + " --estimates " +
                          shell_quote(csv_path) + " --out " + shell_quote(plot_path) + " --title " +
                          shell_quote("vmass-replay " + name + ": " + input_path);
    if (!truth_path.empty()) command += " --truth " + shell_quote(truth_path);
    const int rc = std::system(command.c_str());
    if (out_path.empty()) fs::remove(csv_path);
    if (rc != 0) {
      std::cerr << "vmass-replay: plotting failed (" << command << ")\n";
      return 1;
    }
    if (!json) std::cout << "plot                 " << plot_path << "\n";
  }
  return 0;
}
