#include "fleet_replay.hpp"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <thread>

#include "vmass/io/regular_file.hpp"
#include "vmass/replay/replay_run.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/log_frame_source.hpp"

namespace vmass {
namespace {

namespace fs = std::filesystem;

/// A folder's *.log files that are regular files, sorted by name; the other *.log entries into
/// *skipped as "path: why". "" or why the folder cannot be read.
std::string logs_in(const fs::path& dir, std::vector<std::string>* logs,
                    std::vector<std::string>* skipped) {
  std::error_code ec;
  std::vector<std::string> found;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".log") found.push_back(it->path().string());
  }
  if (ec) return dir.string() + ": cannot read the folder: " + ec.message();
  std::sort(found.begin(), found.end());
  for (std::string& path : found) {
    if (std::string why = io::check_input_file(path, false); !why.empty()) {
      skipped->push_back(path + ": skipped: " + why + " (a folder gives its regular *.log files)");
    } else {
      logs->push_back(std::move(path));
    }
  }
  return "";
}

/// Longest line of a list of logs (a path is at most PATH_MAX, 4096 bytes).
constexpr std::size_t kMaxListLineBytes = 4096;

/// The paths a list file names; "" or why it cannot be read ("list:LINE: why" for a line).
std::string read_list(const std::string& list_file, std::vector<std::string>* paths) {
  const io::FileText file = io::read_regular_file(list_file, io::kMaxListBytes, "list of logs");
  if (!file.ok()) return file.error;
  std::size_t begin = 0;
  for (int line_no = 1; begin < file.text.size(); ++line_no) {
    const std::size_t eol = std::min(file.text.find('\n', begin), file.text.size());
    std::string line = file.text.substr(begin, eol - begin);
    begin = eol + 1;
    const std::string where = list_file + ":" + std::to_string(line_no) + ": ";
    if (line.size() > kMaxListLineBytes) {
      return where + "line longer than " + std::to_string(kMaxListLineBytes) + " bytes";
    }
    if (line.find('\0') != std::string::npos) return where + "a NUL byte: not a list of paths";
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty() && line.front() != '#') paths->push_back(line);
  }
  return "";
}

std::string csv_path_for(const std::string& log, const std::string& out_dir) {
  if (out_dir.empty()) return "";
  return (fs::path(out_dir) / fs::path(log).stem()).string() + ".csv";
}

/// Removes an output, when it is a regular file (never a device or a FIFO).
void remove_output(const std::string& path) {
  std::error_code ec;
  if (!path.empty() && fs::is_regular_file(fs::symlink_status(path, ec))) fs::remove(path, ec);
}

FleetLogResult replay_one(const std::string& path, const FleetPlan& plan,
                          const signals::CanInputs& can, const PipelineParams& params) {
  FleetLogResult r;
  r.path = path;
  const std::string csv_path = csv_path_for(path, plan.out_dir);
  // Any CAN log vmass reads, its format found from its content, as --log reads it.
  std::unique_ptr<runtime::LogFrameSource> frames = runtime::open_log_frame_source(path, &r.error);
  if (!frames) return r;
  if (!plan.interface.empty()) frames->select_interface(plan.interface);
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
  scoring::ReplaySummary summary(std::nullopt);
  runtime::TickRun run;
  play_recording(source, step, std::nullopt, {}, &summary, writer.get(), &run);
  if (const runtime::InterfaceSelection* selection = log.interface_selection()) {
    r.other_interface_frames = selection->skipped();  // a failed row's too
  }
  // The log could not be read to its end; not one line could be read, or no frame was on the
  // interface.
  std::string failed = source.read_error();
  if (failed.empty()) failed = log.no_frames_reason();
  if (!failed.empty()) {
    if (writer) writer->close();
    remove_output(csv_path);
    r.error = std::move(failed);
    return r;
  }
  // The end of the log: the open Bayes batch enters the final estimate, as with --log.
  if (step.flush()) summary.finish(step.pipeline().estimate());
  if (writer && !writer->close()) {
    r.error = csv_path + ": write failed (the file is incomplete)";
    return r;
  }
  r.frames = log.stats().frames;
  r.corrupt_lines = log.stats().corrupt;
  r.estimator = std::string(step.pipeline().regressor().name());
  r.summary = summary.result();
  return r;
}

}  // namespace

std::string collect_logs(const std::vector<std::string>& paths, const std::string& list_file,
                         std::vector<std::string>* logs, std::vector<std::string>* skipped) {
  std::vector<std::string> named = paths;
  if (!list_file.empty()) {
    if (std::string e = read_list(list_file, &named); !e.empty()) return e;
  }
  for (const std::string& p : named) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      if (std::string e = logs_in(p, logs, skipped); !e.empty()) return e;
    } else if (!fs::exists(p, ec)) {
      return p + ": no such log or folder";
    } else if (std::string why = io::check_input_file(p, false); !why.empty()) {
      return p + ": " + why + ": a log named here must be a regular file or a folder";
    } else {
      logs->push_back(p);
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
      results[i] = replay_one(plan.logs[i], plan, can, params);
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
