#include "vmass/runtime/can_input_source.hpp"

#include <algorithm>

namespace vmass::runtime {

CanInputSource::CanInputSource(std::unique_ptr<FrameSource> frames,
                               std::shared_ptr<const can::Decoder> decoder,
                               const signals::SignalMapping& mapping)
    : frames_(std::move(frames)),
      table_(std::move(decoder), mapping),
      plausibility_(mapping.plausibility),
      guarded_(frames_->recorded()) {}

void CanInputSource::sync_counters() {
  counters_.dropped.store(frames_->dropped(), std::memory_order_relaxed);
  counters_.reopens.store(frames_->reopens(), std::memory_order_relaxed);
}

InputSource::Read CanInputSource::next_record(int timeout_ms) {
  for (;;) {
    if (guarded_ && guard_.pop(&frame_, ended_)) {
      publish_clock_counters(guard_.counters());
      return Read::kRecord;
    }
    if (ended_) {
      publish_clock_counters(guard_.counters());
      const std::string problem = frames_->problem();
      set_health(SourceState::kEnded, problem.empty() ? "end of " + frames_->describe() : problem);
      return Read::kEnd;
    }
    can::CanFrame raw;
    const Read r = read_frame(&raw, timeout_ms);
    if (r == Read::kEnd) {
      ended_ = true;
    } else if (r != Read::kRecord) {
      return r;
    } else if (guarded_) {
      guard_.push(raw);
    } else {
      frame_ = raw;  // a live bus: the daemon stamps its frames into the tick clock
      return Read::kRecord;
    }
  }
}

InputSource::Read CanInputSource::read_frame(can::CanFrame* frame, int timeout_ms) {
  const std::int64_t malformed_before = frames_->malformed();
  const FrameSource::Read r = frames_->read(frame, timeout_ms);
  const std::int64_t bad_records = frames_->malformed() - malformed_before;
  if (bad_records > 0) {
    counters_.received.fetch_add(bad_records, std::memory_order_relaxed);
    counters_.malformed.fetch_add(bad_records, std::memory_order_relaxed);
  }
  sync_counters();
  switch (r) {
    case FrameSource::Read::kFrame:
      counters_.received.fetch_add(1, std::memory_order_relaxed);
      set_health(SourceState::kOk, "");
      return Read::kRecord;
    case FrameSource::Read::kTimeout:
      return Read::kTimeout;
    case FrameSource::Read::kDown:
      set_health(SourceState::kDown, frames_->problem());
      return Read::kDown;
    case FrameSource::Read::kEnd:
      return Read::kEnd;
  }
  return Read::kTimeout;
}

std::string CanInputSource::read_error() const {
  return frames_->recorded() ? frames_->problem() : std::string();
}

void CanInputSource::copy_record(InputRecord* record) const {
  record->time_us = frame_.time_us;
  record->frame = frame_;
}

void CanInputSource::apply(const InputRecord& record) {
  const signals::SignalTableCounters& c = table_.counters();
  const std::uint64_t too_short_before = c.malformed;
  table_.on_frame(record.frame, record.time_us);
  counters_.decoded.store(static_cast<std::int64_t>(c.decoded), std::memory_order_relaxed);
  counters_.unknown.store(static_cast<std::int64_t>(c.unknown_id), std::memory_order_relaxed);
  counters_.bus_errors.store(static_cast<std::int64_t>(c.error_frames), std::memory_order_relaxed);
  if (c.malformed != too_short_before) {
    counters_.malformed.fetch_add(static_cast<std::int64_t>(c.malformed - too_short_before),
                                  std::memory_order_relaxed);
  }
}

Sample CanInputSource::sample_at(TimeUs tick_us) {
  Sample s = table_.sample_at(tick_us);
  TimeUs update_us[kInputCount];
  for (int i = 0; i < kInputCount; ++i) {
    update_us[i] = table_.input_state(static_cast<Input>(i)).time_us;
  }
  plausibility_.check(&s, update_us);
  return s;
}

void CanInputSource::health_record(InputHealthRecord* out) const {
  const signals::SignalTableCounters& c = table_.counters();
  for (int i = 0; i < kInputCount; ++i) {
    const auto input = static_cast<Input>(i);
    const signals::InputCounters& ic = c.inputs[static_cast<std::size_t>(i)];
    InputHealthRecord::InputEntry& e = out->inputs[static_cast<std::size_t>(i)];
    e.stale = static_cast<std::int64_t>(ic.stale);
    e.invalid = static_cast<std::int64_t>(ic.invalid_values);
    e.implausible = plausibility_.implausible(input);
    e.counter_fail = static_cast<std::int64_t>(ic.counter_fail);
    e.checksum_fail = static_cast<std::int64_t>(ic.checksum_fail);
    e.verdict = table_.verdict(input).fault != signals::InputFault::kNone
                    ? table_.verdict(input)
                    : plausibility_.verdict(input);
  }
  out->message_count = std::min(table_.watched_count(), InputHealthRecord::kMaxMessages);
  for (int k = 0; k < out->message_count; ++k) {
    const signals::MessageCounters& mc = table_.message_counters(k);
    InputHealthRecord::MessageEntry& m = out->messages[static_cast<std::size_t>(k)];
    m.message = table_.watched_message(k);
    m.valid = table_.message_valid(k);
    m.counter_fail = static_cast<std::int64_t>(mc.counter_fail);
    m.checksum_fail = static_cast<std::int64_t>(mc.checksum_fail);
    m.too_fast = static_cast<std::int64_t>(mc.too_fast);
    m.too_long = static_cast<std::int64_t>(mc.too_long);
  }
  out->bus_valid = table_.bus_valid();
}

std::string CanInputSource::message_name(int message) const {
  const can::Database& db = table_.decoder().database();
  if (message < 0 || message >= static_cast<int>(db.messages.size())) return "";
  return db.messages[static_cast<std::size_t>(message)].name;
}

namespace {

std::string input_line(Input input, const signals::InputCounters& ic, std::int64_t implausible) {
  std::string line = std::string(input_name(input)) + " ";
  if (ic.updates == 0) return line + "never received";
  bool first = true;
  auto add = [&](std::uint64_t n, const char* what) {
    if (n == 0) return;
    line += (first ? "" : ", ") + std::to_string(n) + " " + what;
    first = false;
  };
  add(ic.stale, "stale");
  add(ic.invalid_values, "invalid values");
  add(static_cast<std::uint64_t>(implausible), "implausible");
  add(ic.counter_fail, "counter failures");
  add(ic.checksum_fail, "checksum failures");
  return first ? "" : line;
}

}  // namespace

std::string CanInputSource::input_report() const {
  std::string out;
  const signals::SignalTableCounters& c = table_.counters();
  for (int i = 0; i < kInputCount; ++i) {
    const auto input = static_cast<Input>(i);
    if (!table_.input_state(input).mapped) continue;
    const std::string line =
        input_line(input, c.inputs[static_cast<std::size_t>(i)], plausibility_.implausible(input));
    if (!line.empty()) out += (out.empty() ? "" : "; ") + line;
  }
  for (int k = 0; k < table_.watched_count(); ++k) {
    const signals::MessageCounters& m = table_.message_counters(k);
    if (m.counter_fail + m.checksum_fail + m.too_fast + m.too_long == 0) continue;
    out += (out.empty() ? "" : "; ") + message_name(table_.watched_message(k)) + " " +
           std::to_string(m.counter_fail) + " counter and " + std::to_string(m.checksum_fail) +
           " checksum failures, " + std::to_string(m.too_fast) + " too fast, " +
           std::to_string(m.too_long) + " too long" + (table_.message_valid(k) ? "" : ", invalid");
  }
  return out;
}

}  // namespace vmass::runtime
