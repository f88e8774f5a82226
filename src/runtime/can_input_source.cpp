#include "vmass/runtime/can_input_source.hpp"

namespace vmass::runtime {

CanInputSource::CanInputSource(std::unique_ptr<FrameSource> frames,
                               std::shared_ptr<const can::Decoder> decoder,
                               const signals::SignalMapping& mapping)
    : frames_(std::move(frames)), table_(std::move(decoder), mapping) {}

void CanInputSource::sync_counters() {
  counters_.dropped.store(frames_->dropped(), std::memory_order_relaxed);
  counters_.reopens.store(frames_->reopens(), std::memory_order_relaxed);
}

InputSource::Read CanInputSource::next_record(int timeout_ms) {
  const std::int64_t malformed_before = frames_->malformed();
  const FrameSource::Read r = frames_->read(&frame_, timeout_ms);
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
      set_health(SourceState::kEnded, "end of " + frames_->describe());
      return Read::kEnd;
  }
  return Read::kTimeout;
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

std::string CanInputSource::input_report() const {
  std::string out;
  const signals::SignalTableCounters& c = table_.counters();
  for (int i = 0; i < kInputCount; ++i) {
    const auto input = static_cast<Input>(i);
    const signals::InputCounters& ic = c.inputs[static_cast<std::size_t>(i)];
    if (!table_.input_state(input).mapped) continue;
    if (ic.updates == 0) {
      out += (out.empty() ? "" : "; ") + std::string(input_name(input)) + " never received";
    } else if (ic.stale > 0 || ic.invalid_values > 0) {
      out += (out.empty() ? "" : "; ") + std::string(input_name(input)) + " " +
             std::to_string(ic.stale) + " stale, " + std::to_string(ic.invalid_values) +
             " invalid values";
    }
  }
  return out;
}

}  // namespace vmass::runtime
