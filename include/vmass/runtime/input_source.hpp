// InputSource: where the estimator's inputs come from (a candump log or SocketCAN frames
// through a SignalTable, a samples CSV), in two halves that the daemon gives to two threads:
//
//   reading half      next_record() reads the next record and says when it describes (input
//                     clock: log time for recordings, in time order and with bounded jumps (a
//                     ClockGuard), the tick clock for a live bus); copy_record() copies it into
//                     an InputRecord, which the daemon hands to its estimator thread through an
//                     SPSC queue (so it can pace a recording)
//   table half        apply() folds records into the source's input table; at each tick
//                     sample_at(T) turns the table into the tick's Sample and input_age_us()
//                     says how old each input is
//
// So in the daemon the input table (a SignalTable for CAN, an InputValues for a samples CSV)
// lives on the estimator thread only; nothing in it is shared. Offline (TickDriver) and at
// `--speed max` one thread uses both halves.
//
// Validity rule of the samples-CSV table (sample_at(InputValues...) below):
//
//   input i is valid at tick time T  <=>  its last value was valid
//                                         and T - time_i <= timeout_i
//
// (every row updates every input at its time: a zero-order hold of the rows, each input stale
// once older than its timeout). The CAN table's rule is SignalTable's
// (vmass/signals/signal_table.hpp): per term of each input, timeouts from the `can.inputs`
// mapping or the DBC cycle times.
//
// Implementations: SamplesCsvSource (samples.csv), CanInputSource (a FrameSource of CAN frames
// decoded by a signals::SignalTable, see can_input_source.hpp).
//
// Counters are atomics (each written by one thread, or added to by both) read by the status
// publisher. Thread-safety: next_record()/record_time_us()/copy_record() from one reading thread;
// apply()/sample_at()/input_age_us()/input_report() from one estimator thread; counters(),
// health(), recorded() and describe() from any thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "vmass/can/can_frame.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/runtime/clock_guard.hpp"
#include "vmass/runtime/input_health.hpp"
#include "vmass/runtime/seqlock.hpp"
#include "vmass/signals/input_verdict.hpp"

namespace vmass::runtime {

/// One record on its way from the reading thread to the estimator thread (trivially copyable:
/// goes through SpscQueue). Which member is meaningful depends on the source.
struct InputRecord {
  InputRecord() : frame() {}
  TimeUs time_us = 0;  ///< when the record describes (input clock; may be re-stamped live)
  union {
    can::CanFrame frame;  ///< CanInputSource
    Sample sample;        ///< SamplesCsvSource
  };
};

/// Latest value, time and validity of every input of a samples CSV (trivially copyable).
struct InputValues {
  Sample latest;  ///< values and validity bits of the latest update of each input
  /// signals::kNeverUs: never (any other value is a time, before 1970 too).
  TimeUs input_time_us[kInputCount] = {signals::kNeverUs, signals::kNeverUs, signals::kNeverUs,
                                       signals::kNeverUs, signals::kNeverUs, signals::kNeverUs,
                                       signals::kNeverUs, signals::kNeverUs, signals::kNeverUs,
                                       signals::kNeverUs, signals::kNeverUs, signals::kNeverUs};
  TimeUs last_update_us = signals::kNeverUs;  ///< the latest record applied (input clock)
  std::uint64_t updates = 0;                  ///< records applied
};
static_assert(kInputCount == 12, "update InputValues::input_time_us's initialiser");

/// Per-input timeouts (microseconds) of a samples CSV.
struct InputTimeouts {
  TimeUs timeout_us[kInputCount] = {};
};

/// The tick's Sample at time tick_us from the latest values (see the header comment).
Sample sample_at(const InputValues& values, TimeUs tick_us, const InputTimeouts& timeouts);

/// Counters of a source since start; frames for CAN, rows for a samples CSV. For CAN, decoded,
/// unknown and bus_errors are the SignalTable's (estimator thread); received, dropped and
/// reopens the reader's (reading thread); malformed is added to by both (corrupt records, frames
/// shorter than their DBC message).
struct SourceCounters {
  std::atomic<std::int64_t> received{0};    ///< frames (rows) read
  std::atomic<std::int64_t> decoded{0};     ///< frames of a known message decoded (good rows)
  std::atomic<std::int64_t> unknown{0};     ///< frames of an id not in the DBC
  std::atomic<std::int64_t> malformed{0};   ///< frames too short or of a bad size (bad rows)
  std::atomic<std::int64_t> dropped{0};     ///< frames dropped by the kernel (SO_RXQ_OVFL)
  std::atomic<std::int64_t> bus_errors{0};  ///< CAN error frames
  std::atomic<std::int64_t> reopens{0};     ///< successful re-opens after the input was lost
  // A recording's clock (ClockGuard; reading thread).
  std::atomic<std::int64_t> reordered{0};     ///< records put back in time order
  std::atomic<std::int64_t> late_dropped{0};  ///< records too late for the reorder window
  std::atomic<std::int64_t> time_jumps{0};    ///< clock jumps re-based, stray stamps dropped
};

enum class SourceState : std::uint8_t {
  kOk = 0,  ///< delivering
  kDown,    ///< interface down or gone; being waited for / re-opened
  kEnded,   ///< a recording reached its end
};

/// Trivially copyable health record (published through a SeqLock).
struct SourceHealth {
  SourceState state = SourceState::kOk;
  char detail[120] = {};  ///< last problem, NUL-terminated ("" when none)
};

class InputSource {
 public:
  enum class Read : std::uint8_t {
    kRecord,   ///< a record is ready: record_time_us(), then copy_record()
    kTimeout,  ///< nothing within the timeout (live sources)
    kDown,     ///< the input is lost for now (interface down/gone); call next_record() again
    kEnd,      ///< end of a recording
  };

  virtual ~InputSource() = default;

  // ---------------------------------------------------------------- reading thread
  /// Reads the next record, waiting up to timeout_ms for a live source.
  virtual Read next_record(int timeout_ms) = 0;
  /// Time of the record next_record() read, microseconds (input clock).
  virtual TimeUs record_time_us() const = 0;
  /// Copies the record next_record() read (record->time_us = record_time_us()). Allocates
  /// nothing.
  virtual void copy_record(InputRecord* record) const = 0;

  // ---------------------------------------------------------------- estimator thread
  /// Folds one record into the input table, at record.time_us. Allocates nothing.
  virtual void apply(const InputRecord& record) = 0;
  /// The Sample of a tick at tick_us from the table. Allocates nothing.
  virtual Sample sample_at(TimeUs tick_us) = 0;
  /// tick_us - time of the input's last update (>= 0), or -1 when never received.
  virtual TimeUs input_age_us(Input input, TimeUs tick_us) const = 0;
  /// Per-input problems seen so far ("speed 2 stale, 1 invalid; ..."), "" when none. Allocates:
  /// for the end of a run (after the estimator thread stopped).
  virtual std::string input_report() const { return ""; }
  /// The inputs' health at the latest tick (counts, verdicts, CAN messages). Allocates nothing.
  virtual void health_record(InputHealthRecord* /*out*/) const {}

  // ---------------------------------------------------------------- once reading stopped
  /// Why a recording ended early ("path: read error: ..."), "" after a clean end.
  virtual std::string read_error() const { return ""; }

  // ---------------------------------------------------------------- any thread
  /// A recording (paced by its own time stamps) rather than a live bus.
  virtual bool recorded() const = 0;
  /// E.g. "samples:drive.csv", "replay:drive.log", "socketcan:can0".
  virtual std::string describe() const = 0;
  /// The name of a CAN message of InputHealthRecord::MessageEntry ("" for other sources).
  virtual std::string message_name(int /*message*/) const { return ""; }

  const SourceCounters& counters() const { return counters_; }
  SourceHealth health() const { return health_.read(); }

 protected:
  /// Reading thread only.
  void set_health(SourceState state, const std::string& detail);
  void publish_clock_counters(const ClockCounters& c);

  SourceCounters counters_;

 private:
  SeqLock<SourceHealth> health_;
  SourceState last_state_ = SourceState::kOk;
  std::string last_detail_;
};

std::string_view source_state_name(SourceState s);

}  // namespace vmass::runtime
