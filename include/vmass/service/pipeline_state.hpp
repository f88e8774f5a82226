// Resuming a pipeline from the daemon's state file: what vmassd does at its start, as a
// function the accuracy suite's lifetime mode runs too, so that a vehicle's Nth drive is
// measured through the daemon's own state file (the same file, the same checks: the file's
// checksum and fingerprint, the plausibility of every field, the estimator's own restore).
//
// Reentrant; does file I/O (never from the estimator thread).
#pragma once

#include <string>

#include "vmass/core/pipeline.hpp"
#include "vmass/runtime/tick_step.hpp"

namespace vmass::service {

struct StateRestore {
  bool restored = false;
  bool refused = false;  ///< a state file was there but not restored (why: message)
  std::string message;   ///< what to log; "" when there was no file
};

StateRestore restore_pipeline_state(const std::string& path, Pipeline& pipeline);
/// The same for the daemon's estimator (before its thread starts).
StateRestore restore_pipeline_state(const std::string& path, runtime::TickStep& step);

enum class StateSave {
  kSaved,
  kNothingToSave,  ///< no prior yet: the file (if any) is left as it is
  kNotBelievable,  ///< a state restore would refuse (why: *error); the file is left as it is
  kFailed,         ///< the write failed (why: *error); the file is left as it is
};

/// Saves the pipeline's snapshot, stamped saved_time_us, as vmassd saves it: only a state that
/// restore_pipeline_state() would take back (the same checks), so that a state it refuses is
/// never the one on disk.
StateSave save_pipeline_state(const std::string& path, const PipelineSnapshot& snapshot,
                              TimeUs saved_time_us, const PipelineParams& params,
                              std::string* error);

}  // namespace vmass::service
