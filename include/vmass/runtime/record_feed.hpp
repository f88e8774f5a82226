// RecordFeed: where a TickDriver's records come from, in the order they were read.
//
//   SourceFeed   a recording read on the ticking thread itself (vmass-replay, vmass-calibrate,
//                vmassd --speed max): the next record is always there, until the end
//   RingFeed     records another thread reads and pushes into a RecordRing (vmassd paced or
//                live, record_ring.hpp): the next one may not have arrived yet
//
// Not thread-safe: the ticking thread alone calls a feed. Allocates nothing.
#pragma once

#include "vmass/core/time.hpp"
#include "vmass/runtime/input_source.hpp"

namespace vmass::runtime {

class RecordFeed {
 public:
  enum class Next : std::uint8_t {
    kRecord,  ///< a record is there: its time is in *time_us; take() takes it
    kNotYet,  ///< none for now (a live bus, or a reader thread that lags)
    kEnd,     ///< none ever again: the recording ended and every record was taken
  };

  virtual ~RecordFeed() = default;
  /// Looks at the next record without taking it.
  virtual Next peek(TimeUs* time_us) = 0;
  /// Takes the record peek() saw.
  virtual void take(InputRecord* record) = 0;
  /// After kNotYet: waits a little and returns true when records stamped <= t are still to
  /// come and the tick must wait for them (a recording whose reader lags), false when the tick
  /// goes on without them (a live bus, a stop).
  virtual bool wait_for_more(TimeUs /*t*/) { return false; }
};

/// The records of a recording, read on the ticking thread from the InputSource's reading half.
class SourceFeed final : public RecordFeed {
 public:
  explicit SourceFeed(InputSource& source) : source_(source) {}

  Next peek(TimeUs* time_us) override {
    if (!peeked_) {
      has_record_ = source_.next_record(0) == InputSource::Read::kRecord;
      peeked_ = true;
    }
    if (!has_record_) return Next::kEnd;
    *time_us = source_.record_time_us();
    return Next::kRecord;
  }
  void take(InputRecord* record) override {
    source_.copy_record(record);
    peeked_ = false;
  }

 private:
  InputSource& source_;
  bool peeked_ = false;
  bool has_record_ = false;
};

}  // namespace vmass::runtime
