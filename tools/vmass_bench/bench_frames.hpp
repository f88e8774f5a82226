// The frames the decoding benchmarks decode: random frames of a DBC's messages (uniform over
// the messages, random payloads of the DBC length, seeded), and their candump -l text, which
// cantools decodes for the side-by-side ratio (cantools_bench.py). Messages with overlapping
// signals, which cantools refuses to decode, are left out so that both decode the same frames.
// Set-up code: allocates; not thread-safe.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vmass/can/can_frame.hpp"
#include "vmass/can/decoder.hpp"

namespace vmass::bench {

struct BenchFrames {
  std::vector<can::CanFrame> frames;
  std::string candump_text;   ///< the same frames as a candump -l log
  int messages_used = 0;      ///< messages the frames are drawn from
  int messages_left_out = 0;  ///< messages with overlapping signals
  double signals_per_frame = 0.0;
};

/// `count` frames of the decoder's messages from seed; `overlapping` names the messages to leave
/// out (from the DBC's diagnostics: overlapping_messages()).
BenchFrames random_frames(const can::Decoder& decoder, const std::vector<std::string>& overlapping,
                          int count, std::uint64_t seed);

/// Names of the messages whose signals overlap, from a parse's diagnostics.
std::vector<std::string> overlapping_messages(const can::DbcParseResult& parsed);

/// The frames of `frames` whose message `keep` says to keep (by message index).
std::vector<can::CanFrame> frames_of(const can::Decoder& decoder,
                                     const std::vector<can::CanFrame>& frames,
                                     const std::vector<bool>& keep);

}  // namespace vmass::bench
