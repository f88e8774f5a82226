// CAN input for the daemon: frames from a FrameSource (SocketCAN or a candump -l log), turned
// into estimator inputs by a FrameMapper, behind the InputSource interface of the receive thread.
//
//   FrameSource ──CanFrame──▶ FrameMapper ──▶ InputValues (latest value, time, validity)
//   SocketCanFrameSource        DecodeOnlyMapper (today: DBC decode + counters, no inputs)
//   CandumpFrameSource          the SignalTable of the CAN layer (to come: can.inputs mapping)
//
// FrameMapper is the seam for the signal mapping (DBC message/signal -> Input, unit conversion,
// counters/checksums, timeouts): the daemon only needs apply() and timeouts(). Until the mapping
// exists, DecodeOnlyMapper classifies every frame against the DBC for the status counters
// (decoded, unknown id, too short) and leaves every input invalid, so the estimate reports
// degraded/inputs_invalid rather than anything made up.
//
// Thread-safety: as InputSource (one reading thread).
#pragma once

#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "vmass/can/candump.hpp"
#include "vmass/can/decoder.hpp"
#include "vmass/can/socketcan.hpp"
#include "vmass/service/input_source.hpp"

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

/// Turns frames into input values (the signal-mapping seam).
class FrameMapper {
 public:
  enum class Outcome : std::uint8_t {
    kDecoded,    ///< a known message, decoded (whether or not it fed an input)
    kUnknown,    ///< id not in the DBC
    kMalformed,  ///< shorter than the DBC says (rejected, never zero-filled), or failed checks
    kIgnored,    ///< remote request or error frame
  };
  virtual ~FrameMapper() = default;
  /// Applies one frame (its time_us is the values' time) to *values. Allocates nothing.
  virtual Outcome apply(const can::CanFrame& frame, InputValues* values) = 0;
  virtual InputTimeouts timeouts() const = 0;
};

/// Classifies frames against the DBC and maps no signal (see the header comment).
class DecodeOnlyMapper final : public FrameMapper {
 public:
  explicit DecodeOnlyMapper(const can::Decoder& decoder, double timeout_s = 0.1);
  Outcome apply(const can::CanFrame& frame, InputValues* values) override;
  InputTimeouts timeouts() const override { return timeouts_; }

 private:
  const can::Decoder& decoder_;
  InputTimeouts timeouts_;
};

class CanInputSource final : public InputSource {
 public:
  CanInputSource(std::unique_ptr<FrameSource> frames, std::unique_ptr<FrameMapper> mapper);

  Read read(int timeout_ms) override;
  TimeUs record_time_us() const override { return frame_.time_us; }
  void apply(InputValues* values) override;
  bool recorded() const override { return frames_->recorded(); }
  InputTimeouts timeouts() const override { return mapper_->timeouts(); }
  std::string describe() const override { return frames_->describe(); }

 private:
  void sync_counters();

  std::unique_ptr<FrameSource> frames_;
  std::unique_ptr<FrameMapper> mapper_;
  can::CanFrame frame_;
};

}  // namespace vmass::service
