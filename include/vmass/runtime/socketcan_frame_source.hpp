// SocketCanFrameSource: the frames of a SocketCAN interface (classic and FD, kernel time stamps).
//
// Thread-safety: one reading thread.
#pragma once

#include <memory>
#include <string>

#include "vmass/can/socketcan.hpp"
#include "vmass/runtime/frame_source.hpp"

namespace vmass::runtime {

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

}  // namespace vmass::runtime
