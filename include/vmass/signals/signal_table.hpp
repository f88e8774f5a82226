// SignalTable: the estimator inputs as the CAN bus last reported them, turned into the Sample
// of each estimator tick (DESIGN.md: FrameSource -> Decoder -> SignalTable -> Sample @ tick).
//
// Built once from a compiled DBC and a SignalMapping; afterwards nothing allocates.
//   on_frame(frame, t):  decodes only the mapped signals of the frame's message (a
//                        can::SignalSelection), and commits them all with time t. A term of a
//                        multiplexed signal is updated only when its switch holds the configured
//                        page. A value that is NaN/inf, or outside the DBC's [min|max] (when the
//                        DBC gives a range; tolerance 1e-9 relative), marks the term invalid until
//                        its next good frame. Frames too short for their message are rejected by
//                        the decoder (never zero-filled) and counted; unknown ids are counted.
//   sample_at(now):      input i is valid  <=>  it is mapped, and every term of it
//                                               has been received, its last value was good,
//                                               and now - t_term <= timeout_term
//                        value_i = sum over terms of (dbc_physical * unit_scale * gain) + offset
//                        (gear rounded to the nearest integer). The sample's time is now. An
//                        input that was fresh at the previous call and has timed out now counts
//                        one stale event.
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
#include "vmass/core/sample.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::signals {

struct InputCounters {
  std::uint64_t updates = 0;         ///< term values committed (good or not)
  std::uint64_t invalid_values = 0;  ///< NaN/inf or out of the DBC range
  std::uint64_t stale = 0;           ///< fresh -> timed out transitions seen by sample_at()
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
  bool received = false;  ///< every term has been received at least once
  bool good = false;      ///< received, and every term's last value was good
  double value = 0.0;     ///< SI, sum of the terms' last good values + offset
  TimeUs time_us = -1;    ///< time of the oldest term's last frame; -1 when not received
  TimeUs timeout_us = 0;  ///< the smallest timeout of its terms
};

class SignalTable {
 public:
  SignalTable(std::shared_ptr<const can::Decoder> decoder, const SignalMapping& mapping);

  /// Applies one frame received at time_us. Allocates nothing.
  can::DecodeStatus on_frame(const can::CanFrame& frame, TimeUs time_us);
  can::DecodeStatus on_frame(const can::CanFrame& frame) { return on_frame(frame, frame.time_us); }

  /// The Sample of a tick at now_us (see the header comment). Allocates nothing.
  Sample sample_at(TimeUs now_us);

  InputState input_state(Input input) const;
  /// now_us - time of the input's oldest term (>= 0), or -1 when it was never received.
  TimeUs age_us(Input input, TimeUs now_us) const;

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
    bool has_range = false;
    double minimum = 0.0;
    double maximum = 0.0;
    double tolerance = 0.0;
    TimeUs timeout_us = 0;
    int input = 0;
    // state
    double value_si = 0.0;
    TimeUs time_us = -1;
    bool good = false;
  };
  struct Slot {
    int first_term = 0;
    int term_count = 0;  ///< 0: not mapped
    double offset = 0.0;
    bool fresh = false;  ///< at the previous sample_at()
  };

  std::shared_ptr<const can::Decoder> decoder_;
  SignalMapping mapping_;
  can::SignalSelection selection_;
  std::vector<Term> terms_;  ///< index == selection slot
  std::array<Slot, kInputCount> slots_{};
  SignalTableCounters counters_;
};

}  // namespace vmass::signals
