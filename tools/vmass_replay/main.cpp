// vmass-replay: drive the estimation pipeline offline over recorded samples or a CAN log, at
// the configured tick rate, and report how it did; or over many logs at once.
//
//   vmass-replay --config FILE (--samples CSV | --log LOG [--interface NAME]) [--truth CSV]
//                [--estimator rls|bayes] [--out CSV] [--plot PNG] [--json]
//   vmass-replay --config FILE (--logs PATH... | --log-list FILE) [--interface NAME] [--jobs N]
//                [--out-dir DIR] [--estimator rls|bayes] [--json]
//
// The recording ticks through vmass_runtime exactly as in vmassd (runtime::TickDriver on the
// tick grid T_k = T_0 + k / tick_rate_hz in log time, T_0 the first record's time; tick k sees
// every record stamped at or before T_k; runtime::TickStep): --log decodes a CAN log (candump
// -l, Vector ASC or BLF, PEAK TRC, ASAM MDF4: runtime::LogFrameSource, the format found from the
// content) with the config's `can:` section into a SignalTable, --samples holds samples.csv rows
// (an input older than 5 ticks is stale). Corrupt log lines are reported and counted, never fatal.
// --interface reads one interface of a multi-interface log (runtime/interface_selection.hpp): the
// others' frames are skipped and counted; a log without a frame on it is bad input (2; with many
// logs, a failed row).
// --truth is read only when given, and refused (exit 2) when its time base is not the input's
// (Truth::check_time_base). At the end the open Bayes batch is flushed into the final estimate
// the summary prints. Records out of time order are put back in order within 50 ms, clock
// jumps bounded (runtime::ClockGuard); the counts are reported.
// --logs (files, or folders of *.log files) and --log-list (one path per line) replay many
// logs of one vehicle with the same config, --jobs at a time (default: every core), each as
// --log would; stdout gets one summary table, a CSV row per log (fleet_table.hpp) or with
// --json a JSON line per log, in the order the logs were named; --out-dir writes each log's
// estimate CSV as DIR/<stem>.csv. Exit codes (tools/common/exit_code.hpp): 0 ok, 1 read error in
// the input, write or plot failure (many logs: any log that could not be replayed or written),
// 2 usage, config or input error.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "exit_code.hpp"
#include "fleet_replay.hpp"
#include "fleet_table.hpp"
#include "interface_option.hpp"
#include "vmass/config/config.hpp"
#include "vmass/csv/estimate_csv.hpp"
#include "vmass/io/sibling_program.hpp"
#include "vmass/replay/replay_run.hpp"
#include "vmass/runtime/recording.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/runtime/tick_step.hpp"
#include "vmass/scoring/replay_summary_text.hpp"
#include "vmass/scoring/truth_csv.hpp"
#include "vmass/service/service_config.hpp"

namespace fs = std::filesystem;
namespace rt = vmass::runtime;
using vmass::io::shell_quote;
using vmass::io::sibling_program;
using vmass::tools::kExitFailure;
using vmass::tools::kExitOk;
using vmass::tools::kExitUsage;

namespace {

struct Options {
  std::string config_path, samples_path, log_path, truth_path, out_path, plot_path, estimator;
  std::vector<std::string> logs;  ///< --logs: many logs (files or folders)
  std::string log_list, out_dir;
  std::string interface;                  ///< --interface: "" for every interface of the log(s)
  std::vector<std::string> known_masses;  ///< --known-mass TIME:KG[:STD]
  int jobs = 0;                           ///< 0: every core
  bool json = false;
  bool many() const { return !logs.empty() || !log_list.empty(); }
  const std::string& input_path() const { return log_path.empty() ? samples_path : log_path; }
};

/// --logs and --log-list, and what goes with them only.
void add_many_logs_options(CLI::App& app, Options* o, CLI::Option* single_inputs[4]) {
  auto* logs = app.add_option("--logs", o->logs,
                              "many logs of one vehicle: candump -l files, or folders of *.log");
  auto* list = app.add_option("--log-list", o->log_list, "a file naming one log per line");
  app.add_option("--jobs", o->jobs, "logs replayed at once (default: every core)")
      ->check(CLI::Range(1, 4096));
  app.add_option("--out-dir", o->out_dir, "write each log's estimate CSV as DIR/<stem>.csv");
  for (CLI::Option* many : {logs, list}) {
    for (int i = 0; i < 4; ++i) many->excludes(single_inputs[i]);
  }
}

std::optional<int> parse_options(int argc, char** argv, Options* o) {
  CLI::App app{"vmass-replay: run the mass estimator offline over recorded samples or CAN logs"};
  app.add_option("--config", o->config_path, "vmass YAML config")->required();
  auto* samples = app.add_option("--samples", o->samples_path, "samples CSV (docs/formats.md)");
  auto* log = app.add_option("--log", o->log_path,
                             "CAN log (candump -l, Vector ASC/BLF, PEAK TRC, ASAM MDF4), decoded "
                             "with the config's can: section");
  samples->excludes(log);
  log->excludes(samples);
  vmass::tools::add_interface_option(app, &o->interface)->excludes(samples);
  auto* truth =
      app.add_option("--truth", o->truth_path,
                     "truth CSV (time_s,mass_kg) in the input's time base; none by default");
  app.add_option("--estimator", o->estimator, "override estimator.type")
      ->check(CLI::IsMember({"rls", "bayes"}));
  auto* out = app.add_option("--out", o->out_path, "write the estimate at every tick as CSV");
  auto* plot = app.add_option("--plot", o->plot_path,
                              "write a PNG plot (needs --out or uses a temporary CSV)");
  app.add_flag("--json", o->json,
               "print the summary as one JSON object instead of a table (many logs: JSON lines)");
  auto* known = app.add_option("--known-mass", o->known_masses,
                               "TIME:KG[:STD]: the load's mass is known from TIME s after the "
                               "log's start (a weighbridge ticket); the drive teaches the scale "
                               "(repeatable; STD default 0.5 % of KG)");
  CLI::Option* single_only[4] = {truth, out, plot, known};
  add_many_logs_options(app, o, single_only);
  if (const auto code = vmass::tools::parse_command_line(app, argc, argv)) return code;
  if (o->samples_path.empty() && o->log_path.empty() && !o->many()) {
    std::cerr << "vmass-replay: give the input: --samples CSV, --log LOG or --logs PATH...\n";
    return kExitUsage;
  }
  if (o->many() && (!o->samples_path.empty() || !o->log_path.empty())) {
    std::cerr << "vmass-replay: --logs/--log-list replace --log and --samples\n";
    return kExitUsage;
  }
  if (!o->many() && (o->jobs > 0 || !o->out_dir.empty())) {
    std::cerr << "vmass-replay: --jobs and --out-dir go with --logs or --log-list\n";
    return kExitUsage;
  }
  return std::nullopt;
}

/// Removes an output this run wrote, when it is a regular file (never /dev/null or a FIFO).
void remove_output(const std::string& path) {
  std::error_code ec;
  if (fs::is_regular_file(fs::symlink_status(path, ec))) fs::remove(path, ec);
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
  if (!o.interface.empty()) recording.log->select_interface(o.interface);
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

/// " on can1, N frames of other interfaces skipped" with --interface, else "".
std::string interface_report(const rt::LogFrameSource& log) {
  const rt::InterfaceSelection* selection = log.interface_selection();
  if (selection == nullptr) return "";
  return " on " + selection->name() + ", " + std::to_string(selection->skipped()) +
         " frames of other interfaces skipped";
}

/// What the input held: frames and lines of a log, skipped rows of a samples CSV.
void report_input(const Options& o, const rt::InputSource& source, const rt::LogFrameSource* log,
                  const rt::TickRun& run) {
  report_clock(o, source);
  if (const auto* samples = dynamic_cast<const rt::SamplesCsvSource*>(&source)) {
    for (const auto& w : samples->warnings()) std::cerr << "vmass-replay: warning: " << w << "\n";
    const std::int64_t skipped = source.counters().malformed.load();
    if (skipped > 0) std::cerr << "vmass-replay: skipped " << skipped << " malformed rows\n";
    if (!run.any_record) std::cerr << "vmass-replay: " << o.samples_path << ": no rows\n";
    return;
  }
  const auto& can = dynamic_cast<const rt::CanInputSource&>(source);
  const vmass::signals::SignalTableCounters& c = can.table().counters();
  const vmass::can::CandumpStats& lines = log->stats();
  std::cerr << "vmass-replay: " << o.log_path << " (" << vmass::can::log_format_name(log->format())
            << "): " << lines.frames << " frames" << interface_report(*log) << ", " << lines.corrupt
            << " corrupt " << log->unit() << "s, " << lines.comments << " " << log->unit()
            << "s without a frame (headers, comments, events); decoded " << c.decoded
            << ", unknown id " << c.unknown_id << ", too short " << c.malformed << ", error frames "
            << c.error_frames << "\n";
  const std::string inputs = can.input_report();
  if (!inputs.empty()) std::cerr << "vmass-replay: inputs: " << inputs << "\n";
  if (!run.any_record && log->no_frames_reason().empty()) {
    std::cerr << "vmass-replay: " << o.log_path << ": no frames\n";
  }
}

/// The truth, when --truth names one. False (and a message) when it cannot be read.
bool load_truth(const Options& o, std::optional<vmass::scoring::Truth>* truth) {
  if (o.truth_path.empty()) return true;
  std::string error;
  *truth = vmass::scoring::load_truth_csv(o.truth_path, &error);
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

/// One input (--log or --samples): the summary table (or JSON), the CSV and the plot.
int replay_one_input(const Options& o, const vmass::Config& config,
                     const vmass::PipelineParams& params) {
  std::optional<vmass::scoring::Truth> truth;
  if (!load_truth(o, &truth)) return kExitUsage;
  std::vector<vmass::KnownMassEvent> known;
  if (const std::string bad = parse_known_masses(o.known_masses, params.vehicle, &known);
      !bad.empty()) {
    std::cerr << "vmass-replay: " << bad << "\n";
    return kExitUsage;
  }
  rt::LogFrameSource* log = nullptr;
  std::unique_ptr<rt::InputSource> source = open_input(o, config, &log);
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
  vmass::scoring::ReplaySummary summary(truth);
  rt::TickRun run;
  const std::string refusal =
      vmass::play_recording(*source, step, truth, known, &summary, writer.get(), &run);
  report_input(o, *source, log, run);
  if (const std::string failed = source->read_error(); !failed.empty()) {
    std::cerr << "vmass-replay: " << failed << "\n";  // the run did not read its whole input
    return kExitFailure;
  }
  std::string bad_input;
  if (!refusal.empty()) {
    bad_input = o.truth_path + ": not the truth of " + o.input_path() + ": " + refusal;
  } else if (log != nullptr) {
    bad_input = log->no_frames_reason();  // not one line of the log could be read
  }
  if (!bad_input.empty()) {
    std::cerr << "vmass-replay: " << bad_input << "\n";
    if (writer) writer->close();
    if (!csv_path.empty()) remove_output(csv_path);  // nothing of this run is worth keeping
    return kExitUsage;
  }
  // The end of the input: the open Bayes batch enters the final estimate (the CSV keeps one
  // row per tick; the summary reports the flushed estimate).
  if (step.flush()) summary.finish(step.pipeline().estimate());
  vmass::scoring::record_learnt(step.pipeline(), static_cast<int>(known.size()), &summary);
  vmass::scoring::record_speed_signal(step.pipeline(), &summary);
  vmass::scoring::record_pair_terms(step.pipeline(), &summary);
  if (writer && !writer->close()) {
    std::cerr << "vmass-replay: " << csv_path << ": write failed\n";
    return kExitFailure;
  }
  const std::string name(step.pipeline().regressor().name());
  const vmass::scoring::ReplaySummary::Result result = summary.result();
  std::cout << (o.json ? vmass::scoring::replay_json(result, name) + "\n"
                       : vmass::scoring::replay_table(result, name));
  // No believable mass at the end: the summary says so; the diagnostics say it too.
  const vmass::Estimate& last = step.pipeline().estimate();
  if (last.reason == vmass::StatusReason::kMassImplausible) {
    std::cerr << "vmass-replay: warning: no mass published: " << last.describe_reason() << "\n";
  }
  if (o.plot_path.empty()) return kExitOk;
  const bool plotted = plot(o, csv_path, name);
  if (o.out_path.empty()) fs::remove(csv_path);
  if (!plotted) return kExitFailure;
  if (!o.json) std::cout << "plot                 " << o.plot_path << "\n";
  return kExitOk;
}

/// How much driving the logs held and how fast it went, on stderr.
void report_many(const Options& o, const std::vector<vmass::FleetLogResult>& results,
                 std::size_t skipped, int jobs, double seconds) {
  double driving_s = 0.0;
  long failed = 0;
  std::uint64_t other_interface_frames = 0;
  for (const vmass::FleetLogResult& r : results) {
    driving_s += r.summary.duration_s;
    if (!r.error.empty()) ++failed;
    other_interface_frames += r.other_interface_frames;
  }
  if (!o.interface.empty()) {
    std::cerr << "vmass-replay: interface " << o.interface << ": " << other_interface_frames
              << " frames of other interfaces skipped\n";
  }
  const double n = static_cast<double>(results.size());
  char line[256];
  std::snprintf(line, sizeof line,
                "vmass-replay: %zu logs (%ld failed, %zu skipped), %.2f h of driving in %.2f s "
                "with %d jobs: %.1f logs/s, %.2f h of driving per second\n",
                results.size(), failed, skipped, driving_s / 3600.0, seconds, jobs, n / seconds,
                driving_s / 3600.0 / seconds);
  std::cerr << line;
}

/// Many logs (--logs, --log-list): one summary table on stdout.
int replay_many_logs(const Options& o, const vmass::Config& config,
                     const vmass::PipelineParams& params) {
  vmass::FleetPlan plan;
  std::vector<std::string> skipped;
  std::string error = vmass::collect_logs(o.logs, o.log_list, &plan.logs, &skipped);
  for (const std::string& why : skipped) std::cerr << "vmass-replay: warning: " << why << "\n";
  if (error.empty() && !o.out_dir.empty()) error = vmass::check_csv_names(plan.logs);
  vmass::signals::CanInputsLoad can = vmass::signals::load_can_inputs(config);
  if (error.empty() && !can.ok()) error = can.error;
  if (!error.empty()) {
    std::cerr << "vmass-replay: " << error << "\n";
    return kExitUsage;
  }
  std::error_code ec;
  if (!o.out_dir.empty() && !fs::is_directory(o.out_dir) &&
      !fs::create_directories(o.out_dir, ec)) {
    std::cerr << "vmass-replay: " << o.out_dir << ": cannot make the folder: " << ec.message()
              << "\n";
    return kExitUsage;
  }
  for (const std::string& w : can.inputs->warnings) std::cerr << "vmass-replay: " << w << "\n";
  plan.out_dir = o.out_dir;
  plan.interface = o.interface;
  plan.jobs =
      o.jobs > 0 ? o.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const auto start = std::chrono::steady_clock::now();
  const std::vector<vmass::FleetLogResult> results = vmass::replay_logs(plan, *can.inputs, params);
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  std::string table = o.json ? "" : vmass::fleet_csv_header();
  bool all_ok = true;
  for (const vmass::FleetLogResult& r : results) {
    table += o.json ? vmass::fleet_json_line(r) : vmass::fleet_csv_row(r);
    if (!r.error.empty()) {
      std::cerr << "vmass-replay: " << r.error << "\n";
      all_ok = false;
    }
  }
  std::cout << table;
  report_many(o, results, skipped.size(), plan.jobs, took.count());
  return all_ok ? kExitOk : kExitFailure;
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
  // The daemon's sections too: a config that replays here must not be refused by vmassd.
  if (const auto service = vmass::service::load_service_settings(*loaded.config); !service.ok()) {
    std::cerr << "vmass-replay: " << service.error << "\n";
    return kExitUsage;
  }
  vmass::PipelineParams params = loaded.config->pipeline;
  if (!o.estimator.empty()) {
    params.estimator.type =
        o.estimator == "rls" ? vmass::RegressorType::kRls : vmass::RegressorType::kBayes;
  }
  if (o.many()) return replay_many_logs(o, *loaded.config, params);
  return replay_one_input(o, *loaded.config, params);
}
