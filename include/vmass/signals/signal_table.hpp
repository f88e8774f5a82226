// SignalTable: the estimator inputs as the CAN bus last reported them, turned into the Sample
// of each estimator tick (DESIGN.md: FrameSource -> Decoder -> SignalTable -> Sample @ tick).
//
// Built once from a compiled DBC and a SignalMapping; afterwards nothing allocates.
//   on_frame(frame, t):  a frame of a watched message (one the mapping reads, or one `can.e2e`
//                        protects) passes, in order:
//                          timing     arrivals far above the message's GenMsgCycleTime rate
//                                     (a token bucket: 3 frames of burst, refilled at twice the
//                                     nominal rate) count `too_fast`, and for a message `can.e2e`
//                                     protects fail like a bad counter (a spoofer replaying its
//                                     own counter sequence at ten times the rate passes the
//                                     counter check); a frame longer than its DBC length counts
//                                     `too_long`
//                          E2E        its alive counter and checksum (can/e2e.hpp); a failed
//                                     frame updates nothing and counts against the message and
//                                     every input it feeds; the message is invalid after
//                                     `invalid_after` failures in a row, valid again after
//                                     `valid_after` good frames
//                          commit     the mapped signals of the frame, decoded into a staging
//                                     area and committed all at once with time t (opendbc's
//                                     rule): a term of a multiplexed signal only when its switch
//                                     holds the configured page; a NaN/inf value marks the term
//                                     invalid until its next good frame (as does a value outside
//                                     the DBC's [min|max], but only with can.enforce_dbc_ranges:
//                                     real files carry wrong ranges)
//                        Frames too short for their message are rejected by the decoder (never
//                        zero-filled) and counted; unknown ids are counted.
//   sample_at(now):      input i is valid  <=>  it is mapped, and every term of it
//                                               has been received, its last value was good,
//                                               its message is valid,
//                                               and now - t_term <= timeout_term
//                        value_i = sum over terms of (dbc_physical * unit_scale * gain) + offset
//                        (gear rounded to the nearest integer). The sample's time is now. An
//                        input that was fresh at the previous call and has timed out now counts
//                        one stale event. verdict(i) says why an input is invalid.
// The age of an input is now - (time of its oldest term); a frame time after `now` counts as
// age 0. Times are the caller's clock (log time for a recording, kernel receive time on a bus).
//
// Thread-safety: none inside; one thread owns a SignalTable (the daemon's estimator thread, which
// applies the frames the receive thread hands over, or a replay loop). The Decoder is shared
// read-only.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "vmass/can/decoder.hpp"
#include "vmass/can/e2e.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/signals/input_verdict.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::signals {

struct InputCounters {
  std::uint64_t updates = 0;         ///< term values committed (good or not)
  std::uint64_t invalid_values = 0;  ///< NaN/inf (or out of the DBC range when enforced)
  std::uint64_t stale = 0;           ///< fresh -> timed out transitions seen by sample_at()
  std::uint64_t counter_fail = 0;    ///< frames of a message it reads with a bad alive counter
  std::uint64_t checksum_fail = 0;   ///< frames of a message it reads with a bad checksum
};

/// A watched message's receive health.
struct MessageCounters {
  std::uint64_t frames = 0;         ///< frames of the message, long enough to decode
  std::uint64_t committed = 0;      ///< frames whose values were committed
  std::uint64_t counter_fail = 0;   ///< bad alive counter
  std::uint64_t checksum_fail = 0;  ///< bad checksum
  std::uint64_t withheld = 0;       ///< good frames not committed while the message was invalid
  std::uint64_t too_fast = 0;       ///< arrivals far above the DBC cycle time's rate
  std::uint64_t too_long = 0;       ///< frames longer than the DBC length
};

struct SignalTableCounters {
  std::uint64_t frames = 0;        ///< every frame passed to on_frame()
  std::uint64_t decoded = 0;       ///< of a DBC message, long enough
  std::uint64_t mapped = 0;        ///< decoded and updated at least one input
  std::uint64_t unknown_id = 0;    ///< id not in the DBC
  std::uint64_t malformed = 0;     ///< shorter than the DBC length: rejected
  std::uint64_t remote = 0;        ///< remote requests
  std::uint64_t error_frames = 0;  ///< CAN error frames
  std::array<InputCounters, kInputCount> inputs{};
};

/// The state of one input (see the header comment).
struct InputState {
  bool mapped = false;
  bool received = false;      ///< every term has been received at least once
  bool good = false;          ///< received, and every term's last value was good
  double value = 0.0;         ///< SI, sum of the terms' last good values + offset
  TimeUs time_us = kNeverUs;  ///< time of the oldest term's last frame; kNeverUs: not received
  TimeUs timeout_us = 0;      ///< the smallest timeout of its terms
};

class SignalTable {
 public:
  /// Most messages one table watches (mapped or protected).
  static constexpr int kMaxWatchedMessages = 64;

  /// The mapping's terms, and its protection and enforce_dbc_ranges settings.
  SignalTable(std::shared_ptr<const can::Decoder> decoder, const SignalMapping& mapping);

  /// Applies one frame received at time_us. Allocates nothing.
  can::DecodeStatus on_frame(const can::CanFrame& frame, TimeUs time_us);
  can::DecodeStatus on_frame(const can::CanFrame& frame) { return on_frame(frame, frame.time_us); }

  /// The Sample of a tick at now_us (see the header comment). Allocates nothing.
  Sample sample_at(TimeUs now_us);
  /// Why input i was invalid at the last sample_at() (kNone when valid or not mapped).
  const InputVerdict& verdict(Input input) const {
    return verdicts_[static_cast<std::size_t>(input)];
  }

  InputState input_state(Input input) const;
  /// now_us - time of the input's oldest term (>= 0), or -1 when it was never received.
  TimeUs age_us(Input input, TimeUs now_us) const;

  /// Watched messages: those the mapping reads and those `can.e2e` protects, in DBC order.
  int watched_count() const { return static_cast<int>(messages_.size()); }
  int watched_message(int slot) const { return messages_[static_cast<std::size_t>(slot)].index; }
  bool message_valid(int slot) const {
    return messages_[static_cast<std::size_t>(slot)].validity.valid();
  }
  const MessageCounters& message_counters(int slot) const {
    return messages_[static_cast<std::size_t>(slot)].counters;
  }
  /// Every watched message is valid.
  bool bus_valid() const;

  /// Forgets every value (counters are kept), e.g. when a recording restarts.
  void reset();

  const SignalTableCounters& counters() const { return counters_; }
  const can::Decoder& decoder() const { return *decoder_; }
  const std::shared_ptr<const can::Decoder>& shared_decoder() const { return decoder_; }
  const SignalMapping& mapping() const { return mapping_; }

 private:
  struct Term {
    const can::CompiledSignal* mux_switch = nullptr;  ///< into the decoder; null: not muxed
    std::uint64_t mux_value = 0;
    double scale = 1.0;
    bool has_range = false;  ///< the DBC's, enforced only with can.enforce_dbc_ranges
    double minimum = 0.0;
    double maximum = 0.0;
    double tolerance = 0.0;
    TimeUs timeout_us = 0;
    int input = 0;
    int message_slot = 0;  ///< into messages_
    // state
    double value_si = 0.0;
    TimeUs time_us = kNeverUs;
    bool good = false;
  };
  struct Slot {
    int first_term = 0;
    int term_count = 0;  ///< 0: not mapped
    double offset = 0.0;
    bool fresh = false;  ///< at the previous sample_at()
  };
  struct Watched {
    int index = -1;  ///< message in the DBC
    const can::E2eProfile* e2e = nullptr;
    can::E2eState e2e_state;
    can::MessageValidity validity{5, 2};
    TimeUs resync_after_us = 0;  ///< a gap this long restarts the alive counter
    TimeUs last_time_us = kNeverUs;
    double tokens = 0.0;         ///< too-fast token bucket (frames)
    double tokens_per_us = 0.0;  ///< 0: no cycle time, not checked
    std::uint8_t length = 0;     ///< DBC length
    InputMask feeds = 0;         ///< inputs with a term in it
    MessageCounters counters;
  };
  /// A decoded term value, held until the frame is committed.
  struct Staged {
    int term = 0;
    double physical = 0.0;
  };

  void add_watched(int message, const SignalMapping& mapping);
  void count_status(can::DecodeStatus status, bool used);
  /// Timing and E2E of a watched message's frame; true when its values may be committed.
  bool admit(Watched& w, const can::CanFrame& frame, TimeUs time_us);
  /// Counts too_fast and too_long; true when the frame came too fast.
  bool count_timing(Watched& w, const can::CanFrame& frame, TimeUs time_us);
  void count_e2e_failure(Watched& w, can::E2eResult result);
  /// Decodes the terms of a frame of message m into staged_ and commits them all; true when
  /// any was.
  bool commit(int m, const can::CanFrame& frame, TimeUs time_us);
  /// Input i at now_us: its value into *value, or why it is invalid.
  InputFault evaluate(int i, TimeUs now_us, double* value);

  std::shared_ptr<const can::Decoder> decoder_;
  SignalMapping mapping_;
  can::SignalSelection selection_;
  std::vector<Term> terms_;  ///< index == selection slot
  std::array<Slot, kInputCount> slots_{};
  std::vector<Watched> messages_;
  std::vector<int> watched_slot_;  ///< per DBC message: index into messages_, or -1
  std::vector<Staged> staged_;     ///< capacity: the most terms one message has
  std::array<InputVerdict, kInputCount> verdicts_{};
  SignalTableCounters counters_;
};

}  // namespace vmass::signals
