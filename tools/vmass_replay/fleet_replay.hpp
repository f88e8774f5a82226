// Many logs at once (vmass-replay --logs / --log-list): every log of a fleet replayed with one
// config, a log per worker thread (--jobs, default every core), each exactly as `--log` alone
// replays it (its own SignalTable and Pipeline; the compiled DBC shared read-only), with one
// summary row per log in the order the logs were named (fleet_table.hpp).
//
// Thread-safety: replay_logs() starts and joins its own workers; call it from one thread.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vmass/core/pipeline.hpp"
#include "vmass/scoring/replay_summary.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass {

/// What replaying one log of many gave.
struct FleetLogResult {
  std::string path;
  std::string error;  ///< "" when replayed (and its CSV written); else why not
  std::uint64_t frames = 0;
  std::uint64_t corrupt_lines = 0;
  std::uint64_t other_interface_frames = 0;  ///< skipped: not FleetPlan::interface's (a
                                             ///< failed row's too)
  std::string estimator;
  scoring::ReplaySummary::Result summary;
};

struct FleetPlan {
  std::vector<std::string> logs;
  int jobs = 1;
  std::string out_dir;  ///< "" or a folder for each log's estimate CSV, <stem>.csv
  /// "" or the one interface of each log to replay (runtime/interface_selection.hpp); a log
  /// without a frame on it is a failed row
  std::string interface;
};

/// The logs `paths` names (a file as it is, a folder as its *.log files sorted by name), then
/// those listed one per line in `list_file` ("" for none; blank lines and '#' comments skipped;
/// read whole, a regular file of at most io::kMaxListBytes). A log named must be a regular file;
/// a folder's *.log entries that are not (FIFOs, folders, devices, dangling links) go into
/// *skipped as "path: skipped: why". "" or why they cannot be collected (a path that does not
/// exist or is not a regular file, a list that cannot be read, no log at all).
std::string collect_logs(const std::vector<std::string>& paths, const std::string& list_file,
                         std::vector<std::string>* logs, std::vector<std::string>* skipped);

/// "" or why the per-log estimate CSVs in out_dir would overwrite each other (two logs with
/// the same stem).
std::string check_csv_names(const std::vector<std::string>& logs);

/// Replays every log of the plan (see the header comment); results in the order of plan.logs.
std::vector<FleetLogResult> replay_logs(const FleetPlan& plan, const signals::CanInputs& can,
                                        const PipelineParams& params);

}  // namespace vmass
