// One CAN log replayed for Python (vmass.replay): what `vmass-replay --log LOG --json --out CSV`
// does, the same library calls in the same order (the config and the daemon's sections checked,
// runtime::open_log_recording, play_recording, the open Bayes batch flushed into the summary),
// with the estimates as columns instead of a CSV; and, with a state file, what `vmassd --replay
// LOG --speed max --state-file FILE` does to it: restored before the first tick, saved after
// the last (service::restore_pipeline_state, save_pipeline_state).
// No Python here: the module (module.cpp) releases the GIL around replay_log().
// Reentrant: replays on different threads share only the read-only Config.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "estimate_columns.hpp"
#include "vmass/config/config.hpp"

namespace vmass::python {

struct ConfigResult {
  std::shared_ptr<const Config> config;
  std::string error;  ///< "file:line: key: message" when config is null
};

/// The config as vmass-replay reads it: the YAML, then the daemon's `lcm:` and `daemon:`.
ConfigResult load_replay_config(const std::string& path);

struct ReplayOptions {
  std::string interface;                  ///< "" for every interface of the log
  std::string estimator;                  ///< "" for the config's, else "rls" or "bayes"
  std::string truth_path;                 ///< "" or a truth CSV in the log's time base
  std::vector<std::string> known_masses;  ///< TIME:KG[:STD], as --known-mass
  std::string state_path;                 ///< "" or vmassd's state file, read and written
};

struct ReplayOutcome {
  std::string error;       ///< "" when replayed; else why not (nothing else is set then)
  bool bad_input = false;  ///< the error is the input's (vmass-replay's exit 2), not a read's
  EstimateColumns estimates;
  std::string summary_json;  ///< scoring::replay_json(), vmass-replay --json's object
  std::string log_format;
  std::uint64_t frames = 0, corrupt = 0, other_interface_frames = 0;
  std::vector<std::string> warnings;  ///< DBC deviations, corrupt lines (the first 10), clock
  std::string state_message;          ///< what the restore said ("" without a state file)
  bool state_restored = false;
  bool state_saved = false;
  std::string state_save_error;  ///< "" or why the state was not saved (the file is kept)
};

ReplayOutcome replay_log(const Config& config, const std::string& log,
                         const ReplayOptions& options);

}  // namespace vmass::python
