// End-to-end protection of a message, as AUTOSAR E2E and opendbc check it on receive: an alive
// counter and a checksum per frame, and the message's validity from its frames' results.
//
//   checksum   the checksum signal's raw value must equal algorithm(data id, covered bytes)
//              (can/checksum.hpp); checked first
//   counter    with c the counter's raw value and c' the previous frame's,
//                  1 <= (c - c') mod 2^length <= max_counter_step
//              (a frozen frame repeats its counter, a replayed one jumps, a spoofed one
//              interleaves); the first frame, and the first after a gap longer than the
//              message's timeout, only set c'. c' follows every frame, good or not (opendbc):
//              one bad frame costs one frame, not the stream.
//   validity   the message turns invalid after `invalid_after` consecutive failed frames and
//              valid again after `valid_after` consecutive good ones. A frame's values are
//              committed only when it passed and the message is valid (the frame that makes it
//              valid again included); a failed frame updates nothing.
//
// Per frame: a few shifts, one pass over at most 64 bytes; no allocation.
// Thread-safety: profiles are immutable; an E2eState belongs to the thread that owns its table.
#pragma once

#include <cstdint>

#include "vmass/can/checksum.hpp"
#include "vmass/can/decoder.hpp"

namespace vmass::can {

/// One message's protection, resolved against the DBC at configuration time.
struct E2eProfile {
  SignalRef counter;  ///< invalid: no alive counter
  std::uint32_t max_counter_step = 1;
  SignalRef checksum;  ///< invalid: no checksum
  ChecksumFunction algorithm = nullptr;
  std::uint32_t data_id = 0;
  bool has_data_id = false;
  std::uint64_t covered_bytes = 0;  ///< bit i set: payload byte i is covered (payload order)
};

enum class E2eResult : std::uint8_t { kOk, kCounterFail, kChecksumFail };

/// The receive state of one protected message.
struct E2eState {
  std::uint64_t last_counter = 0;
  bool has_counter = false;
};

/// Checks a frame of the profile's message, long enough for it (Decoder::classify gave kOk).
/// `resync`: the message timed out since its last frame, so its counter starts anew.
E2eResult check_e2e(const Decoder& decoder, const E2eProfile& profile, const CanFrame& frame,
                    bool resync, E2eState* state);

/// A message's validity from its frames' results (see the header comment).
class MessageValidity {
 public:
  MessageValidity(int invalid_after, int valid_after)
      : invalid_after_(invalid_after), valid_after_(valid_after) {}
  /// Records a frame's result; true when its values may be committed.
  bool on_frame(bool passed);
  bool valid() const { return valid_; }

 private:
  int invalid_after_;
  int valid_after_;
  bool valid_ = true;
  int failures_ = 0;  ///< consecutive
  int goods_ = 0;     ///< consecutive, while invalid
};

}  // namespace vmass::can
