// ClockGuard: a recording's records put in time order, and its clock's jumps bounded, before
// anything ticks on them. Logs from many hands carry frames out of order, clocks that step, and
// single frames stamped years away; the tick grid must neither tick through 1e14 empty ticks
// nor drop a second of frames without a word.
//
// Records arrive with their raw times r; the guard hands them on with t = r + offset (offset 0
// until a jump), in time order, once no earlier record can still come (t <= newest - window):
//
//   t in [newest - window, newest)     held and put in order      (counted: reordered)
//   t < newest - window, within bound  too late: dropped          (counted: late_dropped)
//   t in (newest + window,             early: held as a candidate until the next record decides:
//         newest + kForwardJumpUs]         the next is at or after it -> accepted (a gap in the
//                                          bus: nothing lost)
//                                          the next is before it -> a stray stamp ahead: dropped
//                                          (counted: time_jumps), so that one early record (two
//                                          frames of a slow message swapped in the log) costs
//                                          itself, not every record behind it; the price: a
//                                          record right after a gap that the next one overtakes
//                                          is taken for a stray too
//   t beyond newest + kForwardJumpUs   off the timeline: the record is held as a candidate
//   or before newest - kBackJumpUs     until the next one decides (counted: time_jumps):
//       the next continues the old timeline  -> the candidate was a stray stamp: dropped
//       the next continues the candidate's   -> the clock jumped: offset re-based so that the
//                                               candidate comes kJumpGapUs after newest (a
//                                               bounded gap: inputs go stale, nothing hangs)
//
// Records with equal times keep their input order. Holding costs one window of records
// (capacity: far more than a window's worth at the busiest bus; should it fill, the oldest is
// dropped, counted as late). Allocates only at construction.
//
// Not thread-safe: the reading thread owns it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "vmass/core/time.hpp"

namespace vmass::runtime {

struct ClockCounters {
  std::int64_t reordered = 0;     ///< records that overtook a later one, put back in order
  std::int64_t late_dropped = 0;  ///< records too late for the reorder window
  std::int64_t time_jumps = 0;    ///< jumps of the clock re-based, and stray stamps dropped
};

template <class Record>
class ClockGuard {
 public:
  static constexpr TimeUs kWindowUs = 50'000;           ///< reorder window
  static constexpr TimeUs kForwardJumpUs = 10'000'000;  ///< a longer gap is a jump
  static constexpr TimeUs kBackJumpUs = 1'000'000;      ///< further back is a jump, not lateness
  static constexpr TimeUs kJumpGapUs = 1'000'000;       ///< the gap a re-based jump leaves

  explicit ClockGuard(std::size_t capacity = 4096) : ring_(round_up(capacity)) {}

  /// Offers a record stamped with its raw time (record.time_us).
  void push(const Record& record) {
    if (!has_newest_) {
      accept(record, record.time_us);
      return;
    }
    if (has_candidate_ && !resolve_candidate(record.time_us)) {
      candidate_ = record;  // off both timelines: it is the one to decide on now
      has_candidate_ = true;
      candidate_early_ = false;
      return;
    }
    const TimeUs t = record.time_us + offset_;
    if (!near(t, newest_) || t > newest_ + kWindowUs) {
      candidate_ = record;
      has_candidate_ = true;
      candidate_early_ = near(t, newest_);
      return;
    }
    if (t < newest_ - kWindowUs) {
      ++counters_.late_dropped;
      return;
    }
    accept(record, t);
  }

  /// The next record in time order whose place is settled; with `flush` (the input ended)
  /// every held one. False when none is ready.
  bool pop(Record* out, bool flush) {
    if (flush && has_candidate_) {  // nothing follows it: early records are kept, strays not
      has_candidate_ = false;
      if (candidate_early_) {
        accept(candidate_, candidate_.time_us + offset_);
      } else {
        ++counters_.time_jumps;
      }
    }
    if (size_ == 0) return false;
    Record& front = ring_[head_];
    if (!flush && front.time_us > newest_ - kWindowUs) return false;
    *out = front;
    head_ = (head_ + 1) & (ring_.size() - 1);
    --size_;
    return true;
  }

  const ClockCounters& counters() const { return counters_; }

 private:
  static std::size_t round_up(std::size_t n) {
    std::size_t p = 2;
    while (p < n) p *= 2;
    return p;
  }

  /// t is on the timeline whose newest time is `newest` (see the header comment).
  static bool near(TimeUs t, TimeUs newest) {
    return t <= newest + kForwardJumpUs && t >= newest - kBackJumpUs;
  }

  /// The record with time t, in order. A full ring (more than `capacity` records within one
  /// window) drops its oldest, counted as late.
  void accept(const Record& record, TimeUs t) {
    if (size_ == ring_.size()) {
      head_ = (head_ + 1) & (ring_.size() - 1);
      --size_;
      ++counters_.late_dropped;
    }
    if (!has_newest_ || t >= newest_) {
      newest_ = t;
      has_newest_ = true;
    } else {
      ++counters_.reordered;
    }
    const std::size_t mask = ring_.size() - 1;
    std::size_t i = (head_ + size_) & mask;
    ring_[i] = record;
    ring_[i].time_us = t;
    ++size_;
    // Insertion from the back: records come almost in order, so this rarely moves any.
    while (i != head_) {
      const std::size_t prev = (i + mask) & mask;
      if (ring_[prev].time_us <= t) break;
      std::swap(ring_[prev], ring_[i]);
      i = prev;
    }
  }

  /// The record after a candidate says which timeline goes on (see the header comment). False
  /// when it is on neither: the candidate was a stray, and so may the record be.
  bool resolve_candidate(TimeUs next_raw_us) {
    has_candidate_ = false;
    if (candidate_early_) {
      const TimeUs candidate_t = candidate_.time_us + offset_;
      const TimeUs next_t = next_raw_us + offset_;
      if (next_t >= candidate_t && near(next_t, candidate_t)) {
        accept(candidate_, candidate_t);  // the bus went on from it: a gap, nothing lost
        return true;
      }
      ++counters_.time_jumps;  // a stray stamp ahead: dropped
      return near(next_t, newest_);
    }
    ++counters_.time_jumps;
    if (near(next_raw_us + offset_, newest_)) return true;  // the candidate was a stray stamp
    const TimeUs candidate_raw = candidate_.time_us;
    if (!near(next_raw_us, candidate_raw)) return false;
    offset_ = newest_ + kJumpGapUs - candidate_raw;  // the clock jumped: re-based
    accept(candidate_, newest_ + kJumpGapUs);
    return true;
  }

  std::vector<Record> ring_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  TimeUs newest_ = 0;
  bool has_newest_ = false;
  TimeUs offset_ = 0;
  Record candidate_{};
  bool has_candidate_ = false;
  bool candidate_early_ = false;  ///< ahead within kForwardJumpUs (else off the timeline)
  ClockCounters counters_;
};

}  // namespace vmass::runtime
