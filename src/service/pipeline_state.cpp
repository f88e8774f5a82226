#include "vmass/service/pipeline_state.hpp"

#include <cstdio>
#include <functional>

#include "vmass/service/state_plausibility.hpp"
#include "vmass/service/state_store.hpp"

namespace vmass::service {
namespace {

/// "" when restore would take the state back, else why not (implausible_state(), and a time
/// that a tick never has).
std::string unbelievable(const PipelineSnapshot& snapshot, TimeUs saved_time_us,
                         const PipelineParams& params) {
  std::string why = implausible_state(snapshot, params);
  if (why.empty() && saved_time_us < 0) {
    why = "saved at a negative time " + std::to_string(saved_time_us) + " us";
  }
  return why;
}

/// The learnt section alone, when the mass section does not fit (StateLoad::learnt_kept).
void restore_learnt_only(const StateLoad& state,
                         const std::function<bool(const PipelineSnapshot&)>& resume_learnt,
                         StateRestore* out) {
  if (!state.learnt_kept) return;
  if (!resume_learnt(state.state.snapshot)) {
    out->message += "; what was learnt about the car is refused too";
    return;
  }
  out->message += "; what was learnt about the car is kept (" +
                  std::to_string(state.state.snapshot.learnt.evidence) + " drives of evidence)";
}

/// The checks, then `resume(snapshot)`; `pipeline` is read for its parameters and, once
/// restored, its estimate.
StateRestore restore_checked(const std::string& path, const Pipeline& pipeline,
                             const std::function<bool(const PipelineSnapshot&)>& resume,
                             const std::function<bool(const PipelineSnapshot&)>& resume_learnt) {
  StateRestore out;
  const StateLoad state = load_state_file(path, state_fingerprint(pipeline.params()),
                                          learnt_fingerprint(pipeline.params()));
  if (state.status == StateLoadStatus::kMissing) return out;
  out.refused = true;
  if (state.status == StateLoadStatus::kRejected) {
    out.message = state.error + "; starting fresh";
    restore_learnt_only(state, resume_learnt, &out);
    return out;
  }
  const std::string implausible =
      unbelievable(state.state.snapshot, state.state.saved_time_us, pipeline.params());
  if (!implausible.empty()) {
    out.message = path + ": saved state not believable (" + implausible + "); starting fresh";
    return out;
  }
  PipelineSnapshot snapshot = state.state.snapshot;
  snapshot.time_us = state.state.saved_time_us;  // the file keeps it beside the snapshot
  if (!resume(snapshot)) {
    out.message = path + ": saved state refused by the estimator; starting fresh";
    return out;
  }
  out.refused = false;
  out.restored = true;
  char mass[32];
  std::snprintf(mass, sizeof mass, "%.1f", pipeline.estimate().mass_kg);
  out.message = "restored " + std::string(regressor_type_name(pipeline.params().estimator.type)) +
                " estimate " + mass + " kg from " + path + " (" +
                std::to_string(state.state.snapshot.pairs_used) + " pairs); " +
                (pipeline.params().suspension.carries_load() ? "a standstill" : "the drive") +
                " will re-check the load";
  if (!state.learnt_dropped.empty()) out.message += "; " + state.learnt_dropped;
  return out;
}

}  // namespace

StateRestore restore_pipeline_state(const std::string& path, Pipeline& pipeline) {
  return restore_checked(
      path, pipeline, [&](const PipelineSnapshot& s) { return pipeline.restore(s); },
      [&](const PipelineSnapshot& s) { return pipeline.restore_learnt(s); });
}

StateRestore restore_pipeline_state(const std::string& path, runtime::TickStep& step) {
  return restore_checked(
      path, step.pipeline(), [&](const PipelineSnapshot& s) { return step.restore(s); },
      [&](const PipelineSnapshot& s) { return step.restore_learnt(s); });
}

StateSave save_pipeline_state(const std::string& path, const PipelineSnapshot& snapshot,
                              TimeUs saved_time_us, const PipelineParams& params,
                              std::string* error) {
  if (!snapshot.has_prior) return StateSave::kNothingToSave;
  const std::string implausible = unbelievable(snapshot, saved_time_us, params);
  if (!implausible.empty()) {
    *error = "not believable (" + implausible + "): the state on disk is kept";
    return StateSave::kNotBelievable;
  }
  SavedState state;
  state.snapshot = snapshot;
  state.saved_time_us = saved_time_us;
  state.fingerprint = state_fingerprint(params);
  state.learnt_fingerprint = learnt_fingerprint(params);
  return save_state_file(path, state, error) ? StateSave::kSaved : StateSave::kFailed;
}

}  // namespace vmass::service
