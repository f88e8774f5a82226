// SpscQueue: a bounded single-producer single-consumer ring of trivially copyable records
// (vmassd's receive thread hands its records to the estimator thread through one, the estimator
// thread its per-tick records to the publisher thread through another).
//
// Capacity is fixed at construction (rounded up to a power of two); push() never blocks and
// fails when the ring is full (the producer counts the drop), pop() fails when it is empty.
// Lamport's ring with acquire/release indices, each on its own cache line.
//
// Thread-safety: one producer thread and one consumer thread. Allocates only in the constructor.
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <type_traits>

namespace vmass::runtime {

template <class T>
class SpscQueue {
  static_assert(std::is_trivially_copyable<T>::value, "SpscQueue needs a trivially copyable T");

 public:
  explicit SpscQueue(std::size_t capacity) {
    std::size_t n = 2;
    while (n < capacity) n *= 2;
    mask_ = n - 1;
    slots_ = std::make_unique<T[]>(n);
  }
  SpscQueue(const SpscQueue&) = delete;
  SpscQueue& operator=(const SpscQueue&) = delete;

  std::size_t capacity() const { return mask_ + 1; }

  /// Producer: false when full.
  bool push(const T& value) {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) > mask_) return false;
    slots_[head & mask_] = value;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  /// Consumer: false when empty.
  bool pop(T* out) {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    *out = slots_[tail & mask_];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  /// Approximate (exact from the producer or consumer side when the other is idle).
  std::size_t size() const {
    return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire);
  }

 private:
  std::size_t mask_ = 0;
  std::unique_ptr<T[]> slots_;
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
};

}  // namespace vmass::runtime
