#include "vmass/service/lcm_publisher.hpp"

#include <algorithm>
#include <cmath>

#include "vmass/version.hpp"

namespace vmass::service {
namespace {

// A non-finite double must never reach the wire (subscribers compare, plot, log): 0 instead.
double finite_or_zero(double v) { return std::isfinite(v) ? v : 0.0; }

void assign(std::string* out, std::string_view text) { out->assign(text.data(), text.size()); }

}  // namespace

std::string_view daemon_state_name(DaemonState s) {
  switch (s) {
    case DaemonState::kStarting:
      return "starting";
    case DaemonState::kRunning:
      return "running";
    case DaemonState::kInputLost:
      return "input_lost";
    case DaemonState::kInputEnded:
      return "input_ended";
    case DaemonState::kStopping:
      return "stopping";
  }
  return "unknown";
}

void copy_counters(const runtime::SourceCounters& c, DaemonStatus* s) {
  s->frames_received = c.received.load(std::memory_order_relaxed);
  s->frames_decoded = c.decoded.load(std::memory_order_relaxed);
  s->frames_unknown = c.unknown.load(std::memory_order_relaxed);
  s->frames_malformed = c.malformed.load(std::memory_order_relaxed);
  s->frames_dropped = c.dropped.load(std::memory_order_relaxed);
  s->bus_errors = c.bus_errors.load(std::memory_order_relaxed);
  s->source_reopens = c.reopens.load(std::memory_order_relaxed);
}

void to_lcm(const runtime::TickRecord& record, std::string_view estimator,
            vmass::mass_estimate_t* out) {
  const Estimate& e = record.estimate;
  out->utime = e.time_us;
  out->schema_version = kLcmSchemaVersion;
  out->tick = record.tick;
  out->mass_known = e.mass_known;
  out->mass_kg = finite_or_zero(e.mass_kg);
  out->mass_std_kg = finite_or_zero(e.mass_std_kg);
  out->mass_ci_low_kg = finite_or_zero(e.ci_low_kg);
  out->mass_ci_high_kg = finite_or_zero(e.ci_high_kg);
  out->mu_n = finite_or_zero(e.mu_n);
  out->initial_mass_kg = finite_or_zero(e.initial_mass_kg);
  assign(&out->estimator, estimator);
  out->status = static_cast<std::int8_t>(e.status);
  assign(&out->status_name, status_name(e.status));
  out->reason = static_cast<std::int8_t>(e.reason);
  assign(&out->reason_name, reason_name(e.reason));
  out->reason_detail = e.status == EstimateStatus::kConverged ? "" : e.describe_reason();
  out->prior_kind = e.mass_known ? static_cast<std::int8_t>(e.prior_reason) : 0;
  assign(&out->prior_kind_name, e.mass_known ? reason_name(e.prior_reason) : "");
  out->plausible = e.plausible;
  out->rejection_reason = e.plausible ? "" : e.describe_rejection();
  out->mass_model_std_kg = finite_or_zero(e.mass_model_std_kg);
  out->invalid_inputs = static_cast<std::int32_t>(e.invalid_inputs);
  out->pairs_used = e.pairs_used;
  const BlockCounters& lon = e.blocks[static_cast<int>(Block::kLongitudinal)];
  const BlockCounters& lat = e.blocks[static_cast<int>(Block::kLateral)];
  out->longitudinal_ticks = lon.ticks;
  out->longitudinal_accepted = lon.accepted;
  out->longitudinal_rejected = lon.rejected_innovation;
  out->longitudinal_availability = lon.availability();
  out->lateral_ticks = lat.ticks;
  out->lateral_accepted = lat.accepted;
  out->lateral_rejected = lat.rejected_innovation;
  out->lateral_availability = lat.availability();
  out->known_mass = e.known_mass;
  out->learnt_scale = finite_or_zero(e.learnt_scale);
  out->learnt_scale_std = finite_or_zero(e.learnt_scale_std);
}

void to_lcm(const PairEvent& event, Block block, TimeUs tick_us, vmass::pair_t* out) {
  out->utime = tick_us;
  out->block = static_cast<std::int8_t>(block);
  assign(&out->block_name, block_name(block));
  out->has_candidate = event.has_candidate;
  out->accepted = event.verdict == PairVerdict::kAccepted;
  out->verdict = static_cast<std::int8_t>(event.verdict);
  assign(&out->verdict_name, verdict_name(event.verdict));
  out->pair_utime = event.pair.time_us;
  out->y_n = finite_or_zero(event.pair.y_n);
  out->delta_accel_mps2 = finite_or_zero(event.pair.delta_accel_mps2);
  out->weight = finite_or_zero(event.pair.weight);
  out->predicted_y_n = finite_or_zero(event.predicted_y_n);
  out->innovation_variance_n2 = finite_or_zero(event.innovation_variance_n2);
  out->test_ratio = finite_or_zero(event.test_ratio);
  out->rotating_n = finite_or_zero(event.pair.rotating_n);
  out->rotating_mass_kg = finite_or_zero(event.pair.rotating_mass_kg);
  out->gear = static_cast<std::int8_t>(std::clamp(event.pair.gear, -128, 127));
  out->noise_std_n = finite_or_zero(event.pair.noise_std_n);
}

// The per-input counters of schema 2 (zero until their source fills DaemonStatus).
void input_counters_to_lcm(const DaemonStatus& s, vmass::status_t* out) {
  for (auto* v : {&out->input_stale, &out->input_invalid, &out->input_implausible,
                  &out->input_counter_fail, &out->input_checksum_fail}) {
    v->assign(kInputCount, 0);
  }
  out->input_reason.resize(kInputCount);
  for (int i = 0; i < kInputCount; ++i) {
    const auto k = static_cast<std::size_t>(i);
    out->input_stale[k] = s.inputs[k].stale;
    out->input_invalid[k] = s.inputs[k].invalid;
    out->input_implausible[k] = s.inputs[k].implausible;
    out->input_counter_fail[k] = s.inputs[k].counter_fail;
    out->input_checksum_fail[k] = s.inputs[k].checksum_fail;
    out->input_reason[k] = s.inputs[k].reason;
  }
}

void messages_to_lcm(const DaemonStatus& s, vmass::status_t* out) {
  const auto n = s.messages.size();
  out->num_messages = static_cast<std::int32_t>(n);
  out->message_name.resize(n);
  out->message_valid.resize(n);
  out->message_counter_fail.resize(n);
  out->message_checksum_fail.resize(n);
  out->message_too_fast.resize(n);
  out->message_too_long.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const MessageHealth& m = s.messages[i];
    out->message_name[i] = m.name;
    out->message_valid[i] = m.valid;
    out->message_counter_fail[i] = m.counter_fail;
    out->message_checksum_fail[i] = m.checksum_fail;
    out->message_too_fast[i] = m.too_fast;
    out->message_too_long[i] = m.too_long;
  }
  out->bus_valid = s.bus_valid;
}

/// Every verdict's ticks per block (status_t's verdict arrays, vmass::PairVerdict order).
void verdicts_to_lcm(const scoring::VerdictTally& tally, vmass::status_t* out) {
  constexpr int n = static_cast<int>(scoring::kVerdictCount);
  out->num_verdicts = n;
  out->verdict_name.resize(n);
  out->longitudinal_verdict_ticks.resize(n);
  out->lateral_verdict_ticks.resize(n);
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    assign(&out->verdict_name[k], verdict_name(static_cast<PairVerdict>(i)));
    out->longitudinal_verdict_ticks[k] = tally.counts(Block::kLongitudinal)[k];
    out->lateral_verdict_ticks[k] = tally.counts(Block::kLateral)[k];
  }
}

namespace {

/// What is learnt about each gear's rotating mass (schema 5).
void learnt_gears_to_lcm(const Estimate& e, vmass::status_t* out) {
  const int n = std::clamp(e.learnt_gears, 0, kMaxLearntGears);
  out->num_learnt_gears = n;
  out->learnt_gear_correction_kg.resize(static_cast<std::size_t>(n));
  out->learnt_gear_std_kg.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    out->learnt_gear_correction_kg[k] = finite_or_zero(e.learnt_gear_correction_kg[k]);
    out->learnt_gear_std_kg[k] = finite_or_zero(e.learnt_gear_std_kg[k]);
  }
  out->learnt_gear_drives = e.learnt_gear_drives;
}

/// What the tyre watch holds (schema 8).
void tyre_watch_to_lcm(const Estimate& e, vmass::status_t* out) {
  out->tyre_watch_launches = e.tyre_watch_launches;
  out->tyre_watch_stops = e.tyre_watch_stops;
  out->tyre_watch_changes = e.tyre_watch_changes;
  out->tyre_watch_step = finite_or_zero(e.tyre_watch_step);
  out->tyre_watch_step_sigma = finite_or_zero(e.tyre_watch_step_sigma);
  out->tyre_watch_suspected = e.tyre_watch_suspected;
}

/// The drive's pair-term fit (schema 8); the estimate holds zeros when it does not apply.
void pair_fit_to_lcm(const Estimate& e, vmass::status_t* out) {
  out->pair_fit_applies = e.pair_fit_applies;
  out->pair_fit_pairs = e.pair_fit_pairs;
  out->pair_fit_rotating_error = finite_or_zero(e.pair_fit_rotating_error);
  out->pair_fit_rotating_error_std = finite_or_zero(e.pair_fit_rotating_error_std);
  out->pair_fit_converter_multiplied = e.pair_fit_converter_multiplied;
  out->pair_fit_converter_error = finite_or_zero(e.pair_fit_converter_error);
  out->pair_fit_converter_error_std = finite_or_zero(e.pair_fit_converter_error_std);
  out->pair_fit_shift_kg = finite_or_zero(e.pair_fit_shift_kg);
  out->pair_fit_shift_std_kg = finite_or_zero(e.pair_fit_shift_std_kg);
}

}  // namespace

void to_lcm(const DaemonStatus& s, vmass::status_t* out) {
  out->utime = s.last.estimate.time_us;
  out->schema_version = kLcmSchemaVersion;
  out->version = kVersion;  // vmass/version.hpp
  out->uptime_s = finite_or_zero(s.uptime_s);
  out->state = static_cast<std::int8_t>(s.state);
  assign(&out->state_name, daemon_state_name(s.state));
  out->source = s.source;
  out->detail = s.detail;
  out->estimate_status = static_cast<std::int8_t>(s.last.estimate.status);
  assign(&out->estimate_status_name, status_name(s.last.estimate.status));
  out->mass_kg = s.last.estimate.mass_known ? finite_or_zero(s.last.estimate.mass_kg) : 0.0;
  out->driveline_lag_s = s.has_tick ? s.last.estimate.driveline_lag_s : -1.0;
  out->accel_noise_std_mps2 = s.has_tick ? s.last.estimate.accel_noise_std_mps2 : -1.0;
  out->force_noise_std_n = s.has_tick ? s.last.estimate.force_noise_std_n : -1.0;
  out->num_inputs = kInputCount;
  out->input_name.resize(kInputCount);
  out->input_age_s.resize(kInputCount);
  out->input_valid.resize(kInputCount);
  for (int i = 0; i < kInputCount; ++i) {
    const auto k = static_cast<std::size_t>(i);
    assign(&out->input_name[k], input_name(static_cast<Input>(i)));
    out->input_age_s[k] = s.has_tick ? finite_or_zero(s.last.input_age_s[i]) : -1.0;
    out->input_valid[k] = s.has_tick && (s.last.inputs_valid & input_bit(static_cast<Input>(i)));
  }
  input_counters_to_lcm(s, out);
  messages_to_lcm(s, out);
  out->frames_reordered = s.frames_reordered;
  out->frames_late_dropped = s.frames_late_dropped;
  out->time_jumps = s.time_jumps;
  out->frames_received = s.frames_received;
  out->frames_decoded = s.frames_decoded;
  out->frames_unknown = s.frames_unknown;
  out->frames_malformed = s.frames_malformed;
  out->frames_dropped = s.frames_dropped;
  out->bus_errors = s.bus_errors;
  out->source_reopens = s.source_reopens;
  out->ticks = s.timing.ticks;
  out->tick_overruns = s.timing.overruns;
  out->ticks_skipped = s.timing.skipped;
  out->tick_rate_hz = finite_or_zero(s.tick_rate_hz);
  out->jitter_p50_us = finite_or_zero(s.timing.jitter_p50_us);
  out->jitter_p99_us = finite_or_zero(s.timing.jitter_p99_us);
  out->jitter_max_us = finite_or_zero(s.timing.jitter_max_us);
  out->wake_latency_max_us = finite_or_zero(s.timing.wake_latency_max_us);
  out->tick_compute_max_us = finite_or_zero(s.timing.compute_max_us);
  out->publish_queue_drops = s.publish_queue_drops;
  out->publish_failures = s.publish_failures;
  out->state_saves = s.state_saves;
  out->state_restored = s.state_restored;
  verdicts_to_lcm(s.verdicts, out);
  const Estimate& e = s.last.estimate;
  out->learnt_scale = s.has_tick ? finite_or_zero(e.learnt_scale) : 1.0;
  out->learnt_scale_std = s.has_tick ? finite_or_zero(e.learnt_scale_std) : 0.0;
  out->learnt_evidence = s.has_tick ? e.learnt_evidence : 0;
  out->learnt_changes = s.has_tick ? e.learnt_changes : 0;
  out->learnt_anchors = s.has_tick ? e.learnt_anchors : 0;
  out->learnt_tyre_changes = s.has_tick ? e.learnt_tyre_changes : 0;
  out->learnt_evidence_since_tyres = s.has_tick ? e.learnt_evidence_since_tyres : 0;
  out->known_mass = s.has_tick && e.known_mass;
  learnt_gears_to_lcm(s.has_tick ? e : Estimate{}, out);
  tyre_watch_to_lcm(s.has_tick ? e : Estimate{}, out);
  pair_fit_to_lcm(s.has_tick ? e : Estimate{}, out);
  out->commands_received = s.commands_received;
  out->last_command_utime = s.last_command_utime;
  out->last_command_result = s.last_command_result;
}

LcmPublisher::LcmPublisher(lcm::LCM& lcm, const LcmSettings& settings, std::string estimator_name)
    : lcm_(lcm), settings_(settings), estimator_(std::move(estimator_name)) {
  buffer_.resize(64 * 1024);
  for (std::string* s :
       {&estimate_msg_.estimator, &estimate_msg_.status_name, &estimate_msg_.reason_name,
        &pair_msg_.block_name, &pair_msg_.verdict_name}) {
    s->reserve(64);
  }
}

template <class Msg>
bool LcmPublisher::publish(const std::string& channel, const Msg& msg) {
  const int size = msg.getEncodedSize();
  if (size < 0) {
    ++failures_;
    return false;
  }
  if (static_cast<std::size_t>(size) > buffer_.size())
    buffer_.resize(static_cast<std::size_t>(size));
  if (msg.encode(buffer_.data(), 0, size) != size ||
      lcm_.publish(channel, buffer_.data(), static_cast<unsigned int>(size)) != 0) {
    ++failures_;
    return false;
  }
  return true;
}

bool LcmPublisher::on_tick(const runtime::TickRecord& record) {
  bool ok = true;
  if (decimation_count_ == 0) {
    to_lcm(record, estimator_, &estimate_msg_);
    if (publish(settings_.estimate_channel, estimate_msg_)) {
      ++estimates_;
    } else {
      ok = false;
    }
  }
  decimation_count_ = (decimation_count_ + 1) % settings_.estimate_decimation;
  if (settings_.publish_pairs) {
    for (int b = 0; b < kBlockCount; ++b) {
      to_lcm(record.events[static_cast<std::size_t>(b)], static_cast<Block>(b),
             record.estimate.time_us, &pair_msg_);
      ok = publish(settings_.pairs_channel, pair_msg_) && ok;
    }
  }
  return ok;
}

bool LcmPublisher::publish_status(const DaemonStatus& status) {
  to_lcm(status, &status_msg_);
  return publish(settings_.status_channel, status_msg_);
}

}  // namespace vmass::service
