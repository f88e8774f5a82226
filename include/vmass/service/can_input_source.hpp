// CAN input for the daemon: frames from a FrameSource (SocketCAN or a candump -l log) decoded
// into estimator inputs by a signals::SignalTable (the config's `can:` section: DBC + signal
// mapping), behind the InputSource interface:
//
//   reading thread:    FrameSource ──CanFrame──▶ InputRecord ──SpscQueue──▶
//   estimator thread:  SignalTable::on_frame(frame, record time) ... SignalTable::sample_at(T_k)
//
// The SignalTable lives on the estimator thread only (apply/sample_at/input_age_us), so its
// values, ages and counters need no locking; the status counters decoded / unknown / bus_errors
// are copied from the table's counters after every frame, malformed adds the table's too-short
// frames to the reader's corrupt records. A frame is decoded at the record's time (the log time
// of a recording; a live bus's frames are re-stamped into the daemon's tick clock by the reading
// thread), which is what makes `vmassd --replay LOG --speed max` and `vmass-replay --log LOG`
// identical.
//
// Thread-safety: as InputSource.
#pragma once

#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "vmass/can/candump.hpp"
#include "vmass/can/decoder.hpp"
#include "vmass/can/socketcan.hpp"
#include "vmass/service/input_source.hpp"
#include "vmass/signals/signal_table.hpp"

namespace vmass::service {

/// Timestamped CAN frames from somewhere.
class FrameSource {
 public:
  enum class Read : std::uint8_t { kFrame, kTimeout, kDown, kEnd };
  virtual ~FrameSource() = default;
  /// Next frame into *frame, waiting up to timeout_ms for a live bus.
  virtual Read read(can::CanFrame* frame, int timeout_ms) = 0;
  virtual bool recorded() const = 0;
  virtual std::string describe() const = 0;
  /// Why the last read() returned kDown (or a problem worth reporting); "" when none.
  virtual std::string problem() const = 0;
  /// Cumulative frames dropped by the kernel, re-opens after loss, malformed records.
  virtual std::int64_t dropped() const { return 0; }
  virtual std::int64_t reopens() const { return 0; }
  virtual std::int64_t malformed() const { return 0; }
};

/// A candump -l log (can-utils), frames stamped with the log's times. Corrupt lines are counted
/// as malformed and skipped.
class CandumpFrameSource final : public FrameSource {
 public:
  static std::unique_ptr<CandumpFrameSource> open(const std::string& path, std::string* error);
  Read read(can::CanFrame* frame, int timeout_ms) override;
  bool recorded() const override { return true; }
  std::string describe() const override { return "replay:" + path_; }
  std::string problem() const override { return problem_; }
  std::int64_t malformed() const override {
    return static_cast<std::int64_t>(reader_->stats().corrupt);
  }

 private:
  explicit CandumpFrameSource(const std::string& path);
  std::string path_;
  std::ifstream in_;
  std::unique_ptr<can::CandumpReader> reader_;
  std::string problem_;
};

/// A SocketCAN interface (can::SocketCanReader): kernel time stamps (CLOCK_REALTIME), interface
/// down / gone handled by the reader (wait, re-create with backoff); never ends.
class SocketCanFrameSource final : public FrameSource {
 public:
  /// Opens options.interface. When the interface does not exist yet, the source starts without
  /// a socket and keeps re-creating it with backoff (read() says kDown meanwhile). Returns
  /// nullptr and *error only when this kernel cannot do CAN at all (no AF_CAN).
  static std::unique_ptr<SocketCanFrameSource> open(const can::SocketCanOptions& options,
                                                    std::string* error);
  /// Reads from an existing reader (tests: a socketpair through the reader's fd seam).
  SocketCanFrameSource(std::unique_ptr<can::SocketCanReader> reader, std::string interface);

  Read read(can::CanFrame* frame, int timeout_ms) override;
  bool recorded() const override { return false; }
  std::string describe() const override { return "socketcan:" + interface_; }
  std::string problem() const override { return reader_->last_error(); }
  std::int64_t dropped() const override {
    return static_cast<std::int64_t>(reader_->stats().dropped);
  }
  std::int64_t reopens() const override {
    return static_cast<std::int64_t>(reader_->stats().reopens);
  }
  std::int64_t malformed() const override {
    return static_cast<std::int64_t>(reader_->stats().malformed);
  }

 private:
  std::unique_ptr<can::SocketCanReader> reader_;
  std::string interface_;
};

class CanInputSource final : public InputSource {
 public:
  /// Frames from `frames`, decoded and mapped by a SignalTable built from `decoder` and
  /// `mapping` (allocates here, never afterwards).
  CanInputSource(std::unique_ptr<FrameSource> frames, std::shared_ptr<const can::Decoder> decoder,
                 const signals::SignalMapping& mapping);

  Read read(int timeout_ms) override;
  TimeUs record_time_us() const override { return frame_.time_us; }
  void fetch(InputRecord* record) const override;

  void apply(const InputRecord& record) override;
  Sample sample_at(TimeUs tick_us) override { return table_.sample_at(tick_us); }
  TimeUs input_age_us(Input input, TimeUs tick_us) const override {
    return table_.age_us(input, tick_us);
  }
  std::string input_report() const override;

  bool recorded() const override { return frames_->recorded(); }
  std::string describe() const override { return frames_->describe(); }

  /// The table (estimator thread).
  const signals::SignalTable& table() const { return table_; }

 private:
  void sync_counters();

  std::unique_ptr<FrameSource> frames_;
  signals::SignalTable table_;
  can::CanFrame frame_;  ///< reading thread
};

}  // namespace vmass::service
