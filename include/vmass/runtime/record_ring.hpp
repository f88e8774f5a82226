// RecordRing: the records a reader thread hands to the ticking thread (vmassd: receive ->
// estimator), with what the ticking thread needs to tick a recording exactly as offline replay
// does: how far in log time the reader has pushed, and whether it reached the end.
//
//   reader thread     ring.records.push(record); ring.pushed_through_us = T (every record
//                     stamped <= T is in the ring); at the end ring.ended = true
//   ticking thread    RingFeed over the ring, fed to a TickDriver
//
// Thread-safety: one reader thread pushes, one ticking thread pops (SpscQueue); the atomics are
// written by the reader and read by the ticker. Allocates only in the constructor.
#pragma once

#include <atomic>
#include <chrono>
#include <climits>
#include <cstddef>
#include <thread>

#include "vmass/runtime/input_source.hpp"
#include "vmass/runtime/record_feed.hpp"
#include "vmass/runtime/spsc_queue.hpp"

namespace vmass::runtime {

struct RecordRing {
  explicit RecordRing(std::size_t capacity) : records(capacity) {}

  SpscQueue<InputRecord> records;
  /// A recording: every record stamped <= this is in the ring.
  std::atomic<TimeUs> pushed_through_us{INT64_MIN};
  /// The reader pushed its last record (a recording's end; a live reader that stopped).
  std::atomic<bool> ended{false};
};

/// A TickDriver's records from a RecordRing. A recording's tick waits for a lagging reader
/// until every record stamped <= its time has come; a live tick takes what has arrived.
class RingFeed final : public RecordFeed {
 public:
  /// `stop`: a stop request ends every wait.
  RingFeed(RecordRing& ring, bool recording, const std::atomic<bool>& stop)
      : ring_(ring), recording_(recording), stop_(stop) {}

  Next peek(TimeUs* time_us) override {
    if (!has_held_) {
      // Read before the pop: once it is set, every record is in the ring.
      const bool ended = ring_.ended.load(std::memory_order_acquire);
      has_held_ = ring_.records.pop(&held_);
      if (!has_held_) return ended ? Next::kEnd : Next::kNotYet;
    }
    *time_us = held_.time_us;
    return Next::kRecord;
  }
  void take(InputRecord* record) override {
    *record = held_;
    has_held_ = false;
  }
  bool wait_for_more(TimeUs t) override {
    if (!recording_ || stop_.load(std::memory_order_relaxed)) return false;
    if (ring_.pushed_through_us.load(std::memory_order_acquire) >= t) {
      // Every record stamped <= t is in the ring now, but the reader may have pushed one (and
      // moved on) after peek() found the ring empty: look once more before the tick goes on.
      if (looked_again_at_us_ == t) return false;
      looked_again_at_us_ = t;
      return true;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(50));
    return true;
  }

 private:
  RecordRing& ring_;
  bool recording_;
  const std::atomic<bool>& stop_;
  InputRecord held_;  ///< popped, not taken yet (stamped after the tick that looked)
  bool has_held_ = false;
  TimeUs looked_again_at_us_ = INT64_MIN;  ///< the tick whose last look is done
};

}  // namespace vmass::runtime
