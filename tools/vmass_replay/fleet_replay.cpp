#include "fleet_replay.hpp"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <thread>

#include "replay_run.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/log_frame_source.hpp"

namespace vmass {
namespace {

namespace fs = std::filesystem;

/// A folder's *.log files, sorted by name.
std::vector<std::string> logs_in(const fs::path& dir) {
  std::vector<std::string> logs;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().extension() == ".log") logs.push_back(e.path().string());
  }
  std::sort(logs.begin(), logs.end());
  return logs;
}

/// The paths a list file names; "" or why it cannot be read.
std::string read_list(const std::string& list_file, std::vector<std::string>* paths) {
  std::ifstream in(list_file);
  if (!in) return list_file + ": cannot read the list of logs";
  std::string line;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty() && line.front() != '#') paths->push_back(line);
  }
  return "";
}

std::string csv_path_for(const std::string& log, const std::string& out_dir) {
  if (out_dir.empty()) return "";
  return (fs::path(out_dir) / fs::path(log).stem()).string() + ".csv";
}

FleetLogResult replay_one(const std::string& path, const signals::CanInputs& can,
                          const PipelineParams& params, const std::string& csv_path) {
  FleetLogResult r;
  r.path = path;
  // Any CAN log vmass reads, its format found from its content, as --log reads it.
  std::unique_ptr<runtime::LogFrameSource> frames = runtime::open_log_frame_source(path, &r.error);
  if (!frames) return r;
  const runtime::LogFrameSource& log = *frames;
  runtime::CanInputSource source(std::move(frames), can.decoder, can.mapping);
  std::unique_ptr<EstimateCsvWriter> writer;
  if (!csv_path.empty()) {
    writer = std::make_unique<EstimateCsvWriter>(csv_path);
    if (!writer->ok()) {
      r.error = csv_path + ": cannot write";
      return r;
    }
  }
  runtime::TickStep step(params);
  ReplaySummary summary(std::nullopt);
  runtime::TickRun run;
  play_recording(source, step, std::nullopt, &summary, writer.get(), &run);
  if (std::string failed = source.read_error(); !failed.empty()) {
    r.error = std::move(failed);  // the log could not be read to its end
    return r;
  }
  // The end of the log: the open Bayes batch enters the final estimate, as with --log.
  if (step.pipeline().flush()) summary.finish(step.pipeline().estimate());
  if (writer && !writer->close()) r.error = csv_path + ": write failed";
  r.frames = log.stats().frames;
  r.corrupt_lines = log.stats().corrupt;
  r.estimator = std::string(step.pipeline().regressor().name());
  r.summary = summary.result();
  return r;
}

}  // namespace

std::string collect_logs(const std::vector<std::string>& paths, const std::string& list_file,
                         std::vector<std::string>* logs) {
  std::vector<std::string> named = paths;
  if (!list_file.empty()) {
    if (std::string e = read_list(list_file, &named); !e.empty()) return e;
  }
  for (const std::string& p : named) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      const std::vector<std::string> in_dir = logs_in(p);
      logs->insert(logs->end(), in_dir.begin(), in_dir.end());
    } else if (fs::exists(p, ec)) {
      logs->push_back(p);
    } else {
      return p + ": no such log or folder";
    }
  }
  if (logs->empty()) return "no logs found (a folder gives its *.log files)";
  return "";
}

std::string check_csv_names(const std::vector<std::string>& logs) {
  std::set<std::string> stems;
  for (const std::string& log : logs) {
    if (!stems.insert(fs::path(log).stem().string()).second) {
      return log + ": another log has the same name; its estimate CSV would overwrite the other's";
    }
  }
  return "";
}

std::vector<FleetLogResult> replay_logs(const FleetPlan& plan, const signals::CanInputs& can,
                                        const PipelineParams& params) {
  std::vector<FleetLogResult> results(plan.logs.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next.fetch_add(1); i < plan.logs.size(); i = next.fetch_add(1)) {
      results[i] = replay_one(plan.logs[i], can, params, csv_path_for(plan.logs[i], plan.out_dir));
    }
  };
  const std::size_t jobs =
      std::min(plan.logs.size(), static_cast<std::size_t>(std::max(1, plan.jobs)));
  std::vector<std::thread> others;
  for (std::size_t j = 1; j < jobs; ++j) others.emplace_back(worker);
  worker();
  for (std::thread& t : others) t.join();
  return results;
}

}  // namespace vmass
