#include "replay_session.hpp"

#include <optional>
#include <utility>

#include "vmass/replay/replay_run.hpp"
#include "vmass/runtime/interface_selection.hpp"
#include "vmass/runtime/recording.hpp"
#include "vmass/scoring/replay_summary_text.hpp"
#include "vmass/scoring/truth_csv.hpp"
#include "vmass/service/pipeline_state.hpp"
#include "vmass/service/service_config.hpp"

namespace vmass::python {
namespace {

namespace rt = runtime;

/// Corrupt lines reported one by one (the rest are counted), as vmass-replay reports them.
constexpr std::uint64_t kReportedLines = 10;

/// A replay that failed: the input's fault (vmass-replay's exit 2), or a read's (exit 1).
ReplayOutcome failed(std::string why, bool input_fault) {
  ReplayOutcome out;
  out.error = std::move(why);
  out.bad_input = input_fault;
  return out;
}

ReplayOutcome bad_input(std::string why) { return failed(std::move(why), true); }

/// The config's pipeline with the estimator override; "" or why the options are not valid.
std::string pipeline_params(const Config& config, const ReplayOptions& o, PipelineParams* params,
                            std::vector<KnownMassEvent>* known) {
  *params = config.pipeline;
  if (o.estimator == "rls") {
    params->estimator.type = RegressorType::kRls;
  } else if (o.estimator == "bayes") {
    params->estimator.type = RegressorType::kBayes;
  } else if (!o.estimator.empty()) {
    return "estimator '" + o.estimator + "': expected rls or bayes";
  }
  if (!o.interface.empty()) {
    if (std::string e = rt::InterfaceSelection::name_error(o.interface); !e.empty()) {
      return "interface '" + o.interface + "': " + e;
    }
  }
  return parse_known_masses(o.known_masses, params->vehicle, known);
}

/// The recording of `log`, its corrupt lines reported into out->warnings.
rt::LogRecording open_recording(const Config& config, const std::string& log,
                                const ReplayOptions& o, ReplayOutcome* out) {
  rt::LogRecording recording = rt::open_log_recording(log, config);
  if (!recording.source) return recording;
  if (!o.interface.empty()) recording.log->select_interface(o.interface);
  out->warnings = recording.warnings;
  recording.log->on_error([log = recording.log, out](const can::CandumpError& e) {
    if (log->stats().corrupt <= kReportedLines) {
      out->warnings.push_back(e.message + " (" + std::string(log->unit()) + " skipped)");
    }
  });
  return recording;
}

/// What the log held, into *out (frames, lines, the clock's repairs).
void count_input(const rt::LogRecording& recording, ReplayOutcome* out) {
  const rt::LogFrameSource& log = *recording.log;
  out->log_format = std::string(can::log_format_name(log.format()));
  out->frames = log.stats().frames;
  out->corrupt = log.stats().corrupt;
  if (const rt::InterfaceSelection* selection = log.interface_selection()) {
    out->other_interface_frames = selection->skipped();
  }
  const rt::SourceCounters& c = recording.source->counters();
  if (c.reordered != 0 || c.late_dropped != 0 || c.time_jumps != 0) {
    out->warnings.push_back(log.path() + ": time: " + std::to_string(c.reordered) +
                            " records put back in order, " + std::to_string(c.late_dropped) +
                            " too late for the reorder window (dropped), " +
                            std::to_string(c.time_jumps) + " clock jumps or stray time stamps");
  }
}

/// The state after the log, saved as vmassd saves it at its stop (after at least one tick).
void save_state(const ReplayOptions& o, const rt::TickStep& step, const rt::TickRun& run,
                ReplayOutcome* out) {
  if (o.state_path.empty() || run.ticks == 0) return;
  const service::StateSave saved =
      service::save_pipeline_state(o.state_path, step.snapshot(), step.last().estimate.time_us,
                                   step.pipeline().params(), &out->state_save_error);
  out->state_saved = saved == service::StateSave::kSaved;
  if (saved == service::StateSave::kNothingToSave) out->state_save_error = "no prior yet";
}

}  // namespace

ConfigResult load_replay_config(const std::string& path) {
  ConfigLoad loaded = load_config(path);
  if (!loaded.ok()) return {nullptr, loaded.error};
  // The daemon's sections too: a config that replays here must not be refused by vmassd.
  if (const auto service = service::load_service_settings(*loaded.config); !service.ok()) {
    return {nullptr, service.error};
  }
  return {std::make_shared<const Config>(std::move(*loaded.config)), ""};
}

ReplayOutcome replay_log(const Config& config, const std::string& log, const ReplayOptions& o) {
  PipelineParams params;
  std::vector<KnownMassEvent> known;
  if (std::string e = pipeline_params(config, o, &params, &known); !e.empty()) return bad_input(e);
  std::optional<scoring::Truth> truth;
  std::string error;
  if (!o.truth_path.empty() && !(truth = scoring::load_truth_csv(o.truth_path, &error))) {
    return bad_input(error);
  }
  ReplayOutcome out;
  rt::LogRecording recording = open_recording(config, log, o, &out);
  if (!recording.source) return bad_input(recording.error);
  rt::TickStep step(params);
  if (!o.state_path.empty()) {
    const service::StateRestore restore = service::restore_pipeline_state(o.state_path, step);
    out.state_message = restore.message;
    out.state_restored = restore.restored;
  }
  scoring::ReplaySummary summary(truth);
  rt::TickRun run;
  const std::string refusal = play_recording(
      *recording.source, step, truth, known, &summary,
      [&out](const Estimate& e) { out.estimates.add(e); }, &run);
  count_input(recording, &out);
  if (std::string unread = recording.source->read_error(); !unread.empty()) {
    return failed(std::move(unread), false);  // the log could not be read to its end
  }
  if (!refusal.empty())
    return bad_input(o.truth_path + ": not the truth of " + log + ": " + refusal);
  if (std::string none = recording.log->no_frames_reason(); !none.empty()) return bad_input(none);
  // The end of the log: the open Bayes batch enters the final estimate (the columns keep one
  // row per tick), as with vmass-replay --log and at vmassd's stop.
  if (step.flush()) summary.finish(step.pipeline().estimate());
  scoring::record_learnt(step.pipeline(), static_cast<int>(known.size()), &summary);
  scoring::record_speed_signal(step.pipeline(), &summary);
  scoring::record_pair_terms(step.pipeline(), &summary);
  out.summary_json =
      scoring::replay_json(summary.result(), std::string(step.pipeline().regressor().name()));
  save_state(o, step, run, &out);
  return out;
}

}  // namespace vmass::python
