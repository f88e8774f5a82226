// FrameSource: where CAN frames come from (DESIGN.md's data flow): a SocketCAN interface on a
// vehicle, a candump -l log offline. Frames carry their time (kernel stamp or log time); nothing
// downstream knows which source it was.
//
// Thread-safety: one reading thread per source.
#pragma once

#include <cstdint>
#include <string>

#include "vmass/can/can_frame.hpp"

namespace vmass::runtime {

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

}  // namespace vmass::runtime
