// InputHealthRecord: the health of a source's inputs as the estimator thread sees them at a
// tick, handed to the status publisher (status_t's per-input and per-message arrays): per input
// its stale / invalid / implausible / counter-fail / checksum-fail counts and why it is invalid
// now; per watched CAN message its validity and E2E and timing counts; whether the bus is valid
// (every watched message). Trivially copyable: it goes through a SeqLock.
#pragma once

#include <array>
#include <cstdint>

#include "vmass/core/sample.hpp"
#include "vmass/signals/input_verdict.hpp"

namespace vmass::runtime {

struct InputHealthRecord {
  static constexpr int kMaxMessages = 64;

  struct InputEntry {
    std::int64_t stale = 0, invalid = 0, implausible = 0, counter_fail = 0, checksum_fail = 0;
    signals::InputVerdict verdict;  ///< why it is invalid at the tick (kNone: valid)
  };
  struct MessageEntry {
    std::int32_t message = -1;  ///< index in the DBC (InputSource::message_name names it)
    bool valid = true;
    std::int64_t counter_fail = 0, checksum_fail = 0, too_fast = 0, too_long = 0;
  };

  std::array<InputEntry, kInputCount> inputs{};
  std::array<MessageEntry, kMaxMessages> messages{};
  std::int32_t message_count = 0;
  bool bus_valid = true;
};

}  // namespace vmass::runtime
