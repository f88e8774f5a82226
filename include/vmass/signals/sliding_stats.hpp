// Statistics of a window that slides over a series of rows, kept as rows come and go, in O(1)
// a row (amortized): RunningSum, a sum that does not drift, and SlidingSpread, the largest less
// the smallest value. InputPlausibility's cross-checks keep their windows with them.
// Allocate only at construction. Not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vmass::signals {

/// A sum of the values in a window, kept as they come and go. Knuth's TwoSum keeps what each
/// addition rounds off in low_: a plain running sum drifts, and keeps the rounding of large
/// values after they have left.
class RunningSum {
 public:
  void clear() { high_ = low_ = 0.0; }
  void set(double sum) {  ///< recomputed from the window's values
    high_ = sum;
    low_ = 0.0;
  }
  void add(double x);
  void remove(double x) { add(-x); }
  double value() const { return high_ + low_; }
  /// False once a NaN or an infinity went in; it stays after its value has left: set() then.
  bool finite() const;

 private:
  double high_ = 0.0, low_ = 0.0;
};

/// The spread (largest less smallest value) of a window of rows numbered in order, in amortized
/// O(1) a row: at each end, a queue of the rows that can still become the extreme, oldest
/// first. Holds up to `capacity` rows (a power of two). A NaN makes it meaningless until the
/// NaN's row has left.
class SlidingSpread {
 public:
  explicit SlidingSpread(std::size_t capacity) : largest_(capacity), smallest_(capacity) {}
  void clear();
  void push(std::int64_t seq, double value);  ///< the newest row
  void drop_before(std::int64_t seq);         ///< forgets the rows older than seq
  /// Not empty. largest - smallest, bit for bit: smallest_ holds the values negated.
  double spread() const { return largest_.front() + smallest_.front(); }

 private:
  class MaxQueue {  ///< values decreasing from the oldest: the front is the largest
   public:
    explicit MaxQueue(std::size_t capacity) : entries_(capacity), mask_(capacity - 1) {}
    void clear() { front_ = size_ = 0; }
    void push(std::int64_t seq, double value);
    void drop_before(std::int64_t seq);
    double front() const { return entries_[front_].value; }

   private:
    struct Entry {
      std::int64_t seq = 0;
      double value = 0.0;
    };
    Entry& at(std::size_t i) { return entries_[(front_ + i) & mask_]; }
    std::vector<Entry> entries_;
    std::size_t mask_;
    std::size_t front_ = 0, size_ = 0;
  };
  MaxQueue largest_, smallest_;
};

}  // namespace vmass::signals
