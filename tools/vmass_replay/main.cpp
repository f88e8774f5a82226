// vmass-replay: drive the estimation pipeline offline over recorded samples or a CAN log, at
// the configured tick rate, and report how it did.
//
//   vmass-replay --config FILE (--samples CSV | --log LOG) [--truth CSV]
//                [--estimator rls|bayes] [--out CSV] [--plot PNG] [--json]
//
// The recording ticks through vmass_runtime exactly as in vmassd (runtime::TickDriver on the
// tick grid T_k = T_0 + k / tick_rate_hz in log time, T_0 the first record's time; tick k sees
// every record stamped at or before T_k; runtime::TickStep): --log decodes a CAN log (candump
// -l, Vector ASC or BLF, PEAK TRC, ASAM MDF4: runtime::LogFrameSource, the format found from the
// content) with the config's `can:` section into a SignalTable, --samples holds samples.csv rows
// (an input older than 5 ticks is stale). Corrupt log lines are reported and counted, never fatal.
// --truth is read only when given, and refused (exit 2) when its time base is not the input's
// (Truth::check_time_base). At the end the open Bayes batch is flushed into the final estimate
// the summary prints. Records out of time order are put back in order within 50 ms, clock
// jumps bounded (runtime::ClockGuard); the counts are reported. Exit codes
// (tools/common/exit_code.hpp): 0 ok, 1 read error in the input, write or plot failure, 2 usage,
// config or input error.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "exit_code.hpp"
#include "replay_summary.hpp"
#include "vmass/config/config.hpp"
#include "vmass/csv/estimate_csv.hpp"
#include "vmass/runtime/recording.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/runtime/tick_step.hpp"

namespace fs = std::filesystem;
namespace rt = vmass::runtime;
using vmass::tools::kExitFailure;
using vmass::tools::kExitOk;
using vmass::tools::kExitUsage;

namespace {

struct Options {
  std::string config_path, samples_path, log_path, truth_path, out_path, plot_path, estimator;
  bool json = false;
  const std::string& input_path() const { return log_path.empty() ? samples_path : log_path; }
};

std::optional<int> parse_options(int argc, char** argv, Options* o) {
  CLI::App app{"vmass-replay: run the mass estimator offline over recorded samples or a CAN log"};
  app.add_option("--config", o->config_path, "vmass YAML config")->required();
  auto* samples = app.add_option("--samples", o->samples_path, "samples CSV (docs/formats.md)");
  auto* log = app.add_option("--log", o->log_path,
                             "CAN log (candump -l, Vector ASC/BLF, PEAK TRC, ASAM MDF4), decoded "
                             "with the config's can: section");
  samples->excludes(log);
  log->excludes(samples);
  app.add_option("--truth", o->truth_path,
                 "truth CSV (time_s,mass_kg) in the input's time base; none by default");
  app.add_option("--estimator", o->estimator, "override estimator.type")
      ->check(CLI::IsMember({"rls", "bayes"}));
  app.add_option("--out", o->out_path, "write the estimate at every tick as CSV");
  app.add_option("--plot", o->plot_path, "write a PNG plot (needs --out or uses a temporary CSV)");
  app.add_flag("--json", o->json, "print the summary as one JSON object instead of a table");
  if (const auto code = vmass::tools::parse_command_line(app, argc, argv)) return code;
  if (o->samples_path.empty() && o->log_path.empty()) {
    std::cerr << "vmass-replay: give the input: --samples CSV or --log LOG\n";
    return kExitUsage;
  }
  return std::nullopt;
}

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

/// The recording as an InputSource; null (and a message) when it cannot be read.
std::unique_ptr<rt::InputSource> open_input(const Options& o, const vmass::Config& config,
                                            rt::LogFrameSource** log) {
  std::string error;
  if (o.log_path.empty()) {
    const double timeout_s =
        rt::default_samples_timeout_s(config.pipeline.estimator.differencing.tick_rate_hz);
    auto samples = rt::SamplesCsvSource::open(o.samples_path, timeout_s, &error);
    if (!samples) std::cerr << "vmass-replay: " << error << "\n";
    return samples;
  }
  rt::LogRecording recording = rt::open_log_recording(o.log_path, config);
  if (!recording.source) {
    std::cerr << "vmass-replay: " << recording.error << "\n";
    return nullptr;
  }
  for (const std::string& w : recording.warnings) std::cerr << "vmass-replay: " << w << "\n";
  *log = recording.log;
  constexpr std::uint64_t kReportedLines = 10;
  (*log)->on_error([log = *log](const vmass::can::CandumpError& e) {
    if (log->stats().corrupt <= kReportedLines) {  // "path:line: ..." / "path:record N: ..."
      std::cerr << "vmass-replay: " << e.message << " (" << log->unit() << " skipped)\n";
    }
  });
  return std::move(recording.source);
}

/// The recording's clock: records put back in order, too late, clock jumps (all counted).
void report_clock(const Options& o, const rt::InputSource& source) {
  const rt::SourceCounters& c = source.counters();
  if (c.reordered == 0 && c.late_dropped == 0 && c.time_jumps == 0) return;
  std::cerr << "vmass-replay: " << o.input_path() << ": time: " << c.reordered
            << " records put back in order, " << c.late_dropped
            << " too late for the reorder window (dropped), " << c.time_jumps
            << " clock jumps (bounded) or stray time stamps (dropped)\n";
}

/// What the input held: frames and lines of a log, skipped rows of a samples CSV.
void report_input(const Options& o, const rt::InputSource& source, const rt::LogFrameSource* log,
                  const rt::TickRun& run) {
  report_clock(o, source);
  if (const auto* samples = dynamic_cast<const rt::SamplesCsvSource*>(&source)) {
    for (const auto& w : samples->warnings()) std::cerr << "vmass-replay: warning: " << w << "\n";
    const std::int64_t skipped = source.counters().malformed.load();
    if (skipped > 0) std::cerr << "vmass-replay: skipped " << skipped << " malformed rows\n";
    return;
  }
  const auto& can = dynamic_cast<const rt::CanInputSource&>(source);
  const vmass::signals::SignalTableCounters& c = can.table().counters();
  std::cerr << "vmass-replay: " << o.log_path << " (" << vmass::can::log_format_name(log->format())
            << "): " << log->stats().frames << " frames, " << log->stats().corrupt << " corrupt "
            << log->unit() << "s; decoded " << c.decoded << ", unknown id " << c.unknown_id
            << ", too short " << c.malformed << ", error frames " << c.error_frames << "\n";
  const std::string inputs = can.input_report();
  if (!inputs.empty()) std::cerr << "vmass-replay: inputs: " << inputs << "\n";
  if (!run.any_record) std::cerr << "vmass-replay: " << o.log_path << ": no frames\n";
}

/// The truth, when --truth names one. False (and a message) when it cannot be read.
bool load_truth(const Options& o, std::optional<vmass::Truth>* truth) {
  if (o.truth_path.empty()) return true;
  std::string error;
  *truth = vmass::Truth::load(o.truth_path, &error);
  if (!*truth) std::cerr << "vmass-replay: " << error << "\n";
  return truth->has_value();
}

/// Where the estimate CSV goes: --out, or a temporary file for --plot alone ("" for none).
std::string estimate_csv_path(const Options& o) {
  if (!o.out_path.empty() || o.plot_path.empty()) return o.out_path;
  return (fs::temp_directory_path() / ("vmass-replay-" + std::to_string(::getpid()) + ".csv"))
      .string();
}

/// Runs the plotting script on the estimate CSV. False when it failed.
bool plot(const Options& o, const std::string& csv_path, const std::string& estimator_name) {
  std::string command = shell_quote(sibling_program("vmass-plot")) + " --estimates " +
                        shell_quote(csv_path) + " --out " + shell_quote(o.plot_path) + " --title " +
                        shell_quote("vmass-replay " + estimator_name + ": " + o.input_path());
  if (!o.truth_path.empty()) command += " --truth " + shell_quote(o.truth_path);
  command += " >&2";  // its account of the axes goes with the diagnostics, not the summary
  const int rc = std::system(command.c_str());
  if (rc != 0) std::cerr << "vmass-replay: plotting failed (" << command << ")\n";
  return rc == 0;
}

/// One run over the recording: every tick's estimate into the summary and the CSV writer.
/// "" on success, else why the truth was refused (checked at tick 0).
std::string replay(rt::InputSource& source, rt::TickStep& step, const vmass::PipelineParams& params,
                   const std::optional<vmass::Truth>& truth, vmass::ReplaySummary* summary,
                   vmass::EstimateCsvWriter* writer, rt::TickRun* run) {
  const double rate_hz = params.estimator.differencing.tick_rate_hz;
  const vmass::TimeUs tick_period_us = vmass::from_seconds(1.0 / rate_hz);
  std::string truth_refusal;
  rt::UnpacedClock clock;
  rt::TickDriver driver(source, rate_hz);
  *run = driver.run(clock, [&](std::int64_t k, vmass::TimeUs t) {
    if (k == 0 && truth) truth_refusal = truth->check_time_base(t, tick_period_us);
    if (!truth_refusal.empty()) return;
    const vmass::Estimate& e = step.tick(k, t, source).estimate;
    summary->add(e);
    if (writer) writer->write(e);
  });
  return truth_refusal;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto code = parse_options(argc, argv, &o)) return *code;
  vmass::ConfigLoad loaded = vmass::load_config(o.config_path);
  if (!loaded.ok()) {
    std::cerr << "vmass-replay: " << loaded.error << "\n";
    return kExitUsage;
  }
  vmass::PipelineParams params = loaded.config->pipeline;
  if (!o.estimator.empty()) {
    params.estimator.type =
        o.estimator == "rls" ? vmass::RegressorType::kRls : vmass::RegressorType::kBayes;
  }
  std::optional<vmass::Truth> truth;
  if (!load_truth(o, &truth)) return kExitUsage;
  rt::LogFrameSource* log = nullptr;
  std::unique_ptr<rt::InputSource> source = open_input(o, *loaded.config, &log);
  if (!source) return kExitUsage;
  const std::string csv_path = estimate_csv_path(o);
  std::unique_ptr<vmass::EstimateCsvWriter> writer;
  if (!csv_path.empty()) {
    writer = std::make_unique<vmass::EstimateCsvWriter>(csv_path);
    if (!writer->ok()) {
      std::cerr << "vmass-replay: " << csv_path << ": cannot write\n";
      return kExitUsage;
    }
  }

  rt::TickStep step(params);
  vmass::ReplaySummary summary(truth);
  rt::TickRun run;
  const std::string refusal = replay(*source, step, params, truth, &summary, writer.get(), &run);
  report_input(o, *source, log, run);
  if (const std::string failed = source->read_error(); !failed.empty()) {
    std::cerr << "vmass-replay: " << failed << "\n";  // the run did not read its whole input
    return kExitFailure;
  }
  if (!refusal.empty()) {
    std::cerr << "vmass-replay: " << o.truth_path << ": not the truth of " << o.input_path() << ": "
              << refusal << "\n";
    if (writer) writer->close();
    if (!csv_path.empty()) fs::remove(csv_path);  // nothing of this run is worth keeping
    return kExitUsage;
  }
  // The end of the input: the open Bayes batch enters the final estimate (the CSV keeps one
  // row per tick; the summary reports the flushed estimate).
  if (step.pipeline().flush()) summary.finish(step.pipeline().estimate());
  if (writer && !writer->close()) {
    std::cerr << "vmass-replay: " << csv_path << ": write failed\n";
    return kExitFailure;
  }
  const std::string name(step.pipeline().regressor().name());
  std::cout << (o.json ? summary.json(name) + "\n" : summary.table(name));
  if (o.plot_path.empty()) return kExitOk;
  const bool plotted = plot(o, csv_path, name);
  if (o.out_path.empty()) fs::remove(csv_path);
  if (!plotted) return kExitFailure;
  if (!o.json) std::cout << "plot                 " << o.plot_path << "\n";
  return kExitOk;
}
