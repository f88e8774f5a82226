#include "vmass/service/can_input_source.hpp"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <linux/can.h>

namespace vmass::service {

// ------------------------------------------------------------------------------ candump log

CandumpFrameSource::CandumpFrameSource(const std::string& path)
    : path_(path), in_(path, std::ios::binary) {
  reader_ = std::make_unique<can::CandumpReader>(in_, path);
}

std::unique_ptr<CandumpFrameSource> CandumpFrameSource::open(const std::string& path,
                                                             std::string* error) {
  std::unique_ptr<CandumpFrameSource> s(new CandumpFrameSource(path));
  if (!s->in_) {
    if (error) *error = path + ": cannot open the log: " + std::strerror(errno);
    return nullptr;
  }
  return s;
}

FrameSource::Read CandumpFrameSource::read(can::CanFrame* frame, int /*timeout_ms*/) {
  can::CandumpRecord record;
  if (!reader_->next(&record)) return Read::kEnd;
  *frame = record.frame;
  return Read::kFrame;
}

// ------------------------------------------------------------------------------ SocketCAN

std::unique_ptr<SocketCanFrameSource> SocketCanFrameSource::open(
    const can::SocketCanOptions& options, std::string* error) {
  std::string why;
  int fd = can::open_can_socket(options, &why);
  if (fd < 0) {
    // Tell "this kernel has no CAN" (fatal) from "the interface is not there yet" (wait).
    const int probe = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    if (probe < 0 && (errno == EAFNOSUPPORT || errno == EPROTONOSUPPORT)) {
      if (error) *error = options.interface + ": " + why;
      return nullptr;
    }
    if (probe >= 0) ::close(probe);
  }
  auto reader = std::make_unique<can::SocketCanReader>(
      fd, [options](std::string* e) { return can::open_can_socket(options, e); },
      options.reopen_initial_ms, options.reopen_max_ms);
  return std::make_unique<SocketCanFrameSource>(std::move(reader), options.interface);
}

SocketCanFrameSource::SocketCanFrameSource(std::unique_ptr<can::SocketCanReader> reader,
                                           std::string interface)
    : reader_(std::move(reader)), interface_(std::move(interface)) {}

FrameSource::Read SocketCanFrameSource::read(can::CanFrame* frame, int timeout_ms) {
  switch (reader_->read(frame, timeout_ms)) {
    case can::ReadStatus::kFrame:
      return Read::kFrame;
    case can::ReadStatus::kTimeout:
    case can::ReadStatus::kError:  // socket kept; counted by the reader
      return Read::kTimeout;
    case can::ReadStatus::kInterfaceDown:
    case can::ReadStatus::kInterfaceGone:
    case can::ReadStatus::kReopening:
      return Read::kDown;
    case can::ReadStatus::kClosed:
      return Read::kEnd;
  }
  return Read::kTimeout;
}

// ------------------------------------------------------------------------------ source

CanInputSource::CanInputSource(std::unique_ptr<FrameSource> frames,
                               std::shared_ptr<const can::Decoder> decoder,
                               const signals::SignalMapping& mapping)
    : frames_(std::move(frames)), table_(std::move(decoder), mapping) {}

void CanInputSource::sync_counters() {
  counters_.dropped.store(frames_->dropped(), std::memory_order_relaxed);
  counters_.reopens.store(frames_->reopens(), std::memory_order_relaxed);
}

InputSource::Read CanInputSource::read(int timeout_ms) {
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

void CanInputSource::fetch(InputRecord* record) const {
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

}  // namespace vmass::service
