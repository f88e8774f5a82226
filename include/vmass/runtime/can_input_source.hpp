// CAN input for the daemon: frames from a FrameSource (SocketCAN or a candump -l log) decoded
// into estimator inputs by a signals::SignalTable (the config's `can:` section: DBC + signal
// mapping), behind the InputSource interface:
//
//   reading thread:    FrameSource ──CanFrame──▶ InputRecord ──SpscQueue──▶
//   estimator thread:  SignalTable::on_frame(frame, record time) ... SignalTable::sample_at(T_k)
//                      ──▶ InputPlausibility::check (the mapping's can.plausibility)
//
// The SignalTable lives on the estimator thread only (apply/sample_at/input_age_us), so its
// values, ages and counters need no locking; the status counters decoded / unknown / bus_errors
// are copied from the table's counters after every frame, malformed adds the table's too-short
// frames to the reader's corrupt records. A frame is decoded at the record's time (the log time
// of a recording; a live bus's frames are re-stamped into the daemon's tick clock by the reading
// thread), which is what makes `vmassd --replay LOG --speed max` and `vmass-replay --log LOG`
// identical. A recording's frames pass a ClockGuard first (reorder window, bounded jumps).
//
// Thread-safety: as InputSource.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "vmass/can/decoder.hpp"
#include "vmass/runtime/clock_guard.hpp"
#include "vmass/runtime/frame_source.hpp"
#include "vmass/runtime/input_source.hpp"
#include "vmass/signals/input_plausibility.hpp"
#include "vmass/signals/signal_table.hpp"

namespace vmass::runtime {

class CanInputSource final : public InputSource {
 public:
  /// Frames from `frames`, decoded and mapped by a SignalTable built from `decoder` and
  /// `mapping` (allocates here, never afterwards).
  CanInputSource(std::unique_ptr<FrameSource> frames, std::shared_ptr<const can::Decoder> decoder,
                 const signals::SignalMapping& mapping);

  Read next_record(int timeout_ms) override;
  TimeUs record_time_us() const override { return frame_.time_us; }
  void copy_record(InputRecord* record) const override;

  void apply(const InputRecord& record) override;
  /// The table's Sample, through the inputs' plausibility checks.
  Sample sample_at(TimeUs tick_us) override;
  TimeUs input_age_us(Input input, TimeUs tick_us) const override {
    return table_.age_us(input, tick_us);
  }
  std::string input_report() const override;
  void health_record(InputHealthRecord* out) const override;
  std::string message_name(int message) const override;

  std::string read_error() const override;
  bool recorded() const override { return frames_->recorded(); }
  std::string describe() const override { return frames_->describe(); }

  /// The table and the plausibility checks (estimator thread).
  const signals::SignalTable& table() const { return table_; }
  const signals::InputPlausibility& plausibility() const { return plausibility_; }

 private:
  void sync_counters();
  /// One frame from the FrameSource, counted.
  Read read_frame(can::CanFrame* frame, int timeout_ms);

  std::unique_ptr<FrameSource> frames_;
  signals::SignalTable table_;
  signals::InputPlausibility plausibility_;
  // Reading thread:
  can::CanFrame frame_;
  bool guarded_;  ///< a recording: its frames go through the clock guard
  ClockGuard<can::CanFrame> guard_;
  bool ended_ = false;
};

}  // namespace vmass::runtime
