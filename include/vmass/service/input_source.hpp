// InputSource: where the daemon's estimator inputs come from, as seen by its receive thread.
//
// The receive thread keeps an InputValues (the latest value, time and validity of every
// estimator input) and publishes it to the estimator through a SeqLock once per update; at each
// tick the estimator turns the latest InputValues into the tick's Sample with sample_at():
//
//   input i is valid at tick time T  <=>  its last value was valid
//                                         and T - time_i <= timeout_i
//
// (For a samples CSV every row updates every input at its time, so this is exactly the
// zero-order hold of vmass::TickResampler with stale_after = timeout.)
//
// A source delivers records one at a time: read() fetches the next record and says when it
// describes (input clock: log time for recordings, CLOCK_REALTIME kernel stamps for SocketCAN);
// apply() folds it into the InputValues. The split lets the receive thread pace a recording by
// its log time between the two calls. Implementations: SamplesCsvSource (samples.csv),
// CanInputSource (a FrameSource of CAN frames + a FrameMapper, see can_input_source.hpp).
//
// Counters are atomics written by the reading thread and read by the status publisher.
// Thread-safety: read()/apply() from one thread; counters() and health() from any thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "vmass/core/sample.hpp"
#include "vmass/service/seqlock.hpp"

namespace vmass::service {

/// Latest value, time and validity of every input (trivially copyable).
struct InputValues {
  Sample latest;  ///< values and validity bits of the latest update of each input
  TimeUs input_time_us[kInputCount] = {-1, -1, -1, -1, -1, -1, -1, -1, -1};  ///< -1: never
  TimeUs last_update_us = -1;  ///< time of the latest record applied (input clock)
  std::uint64_t updates = 0;   ///< records applied
};
static_assert(kInputCount == 9, "update InputValues::input_time_us's initialiser");

/// Per-input timeouts (microseconds).
struct InputTimeouts {
  TimeUs timeout_us[kInputCount] = {};
};

/// The tick's Sample at time tick_us from the latest values (see the header comment).
Sample sample_at(const InputValues& values, TimeUs tick_us, const InputTimeouts& timeouts);

/// Counters of a source since start; frames for CAN, rows for a samples CSV.
struct SourceCounters {
  std::atomic<std::int64_t> received{0};    ///< frames (rows) read
  std::atomic<std::int64_t> decoded{0};     ///< frames of a known message decoded (good rows)
  std::atomic<std::int64_t> unknown{0};     ///< frames of an id not in the DBC
  std::atomic<std::int64_t> malformed{0};   ///< frames too short or of a bad size (bad rows)
  std::atomic<std::int64_t> dropped{0};     ///< frames dropped by the kernel (SO_RXQ_OVFL)
  std::atomic<std::int64_t> bus_errors{0};  ///< CAN error frames
  std::atomic<std::int64_t> reopens{0};     ///< successful re-opens after the input was lost
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
    kRecord,   ///< a record is ready: record_time_us(), then apply()
    kTimeout,  ///< nothing within the timeout (live sources)
    kDown,     ///< the input is lost for now (interface down/gone); call read() again
    kEnd,      ///< end of a recording
  };

  virtual ~InputSource() = default;

  /// Fetches the next record, waiting up to timeout_ms for a live source.
  virtual Read read(int timeout_ms) = 0;
  /// Time of the record read() fetched, microseconds (input clock).
  virtual TimeUs record_time_us() const = 0;
  /// Folds the fetched record into *values (and counts it).
  virtual void apply(InputValues* values) = 0;

  /// A recording (paced by its own time stamps) rather than a live bus.
  virtual bool recorded() const = 0;
  /// How long each input stays valid after its last update.
  virtual InputTimeouts timeouts() const = 0;
  /// E.g. "samples:drive.csv", "replay:drive.log", "socketcan:can0".
  virtual std::string describe() const = 0;

  const SourceCounters& counters() const { return counters_; }
  SourceHealth health() const { return health_.read(); }

 protected:
  /// Reading thread only.
  void set_health(SourceState state, const std::string& detail);

  SourceCounters counters_;

 private:
  SeqLock<SourceHealth> health_;
  SourceState last_state_ = SourceState::kOk;
  std::string last_detail_;
};

std::string_view source_state_name(SourceState s);

}  // namespace vmass::service
