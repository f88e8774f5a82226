// SeqLock: one writer publishes a small trivially copyable value; any number of readers take
// consistent copies without blocking the writer (the daemon's signal table and state slots).
//
//   write: seq = s + 1 (odd: write in progress), copy the value in, seq = s + 2
//   read:  s1 = seq (retry while odd), copy the value out, s2 = seq, retry unless s1 == s2
//
// The value is stored as relaxed std::atomic words, with fences ordering them against the
// sequence counter (Boehm, "Can seqlocks get along with programming language memory models?",
// 2012), so that there is no data race in the C++ sense (ThreadSanitizer-clean).
//
// Thread-safety: exactly one writer thread at a time; readers from any thread. Wait-free for the
// writer, lock-free for readers (a reader retries while a write overlaps). No allocation.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace vmass::runtime {

template <class T>
class SeqLock {
  static_assert(std::is_trivially_copyable<T>::value, "SeqLock needs a trivially copyable T");

 public:
  SeqLock() { store(T{}); }
  explicit SeqLock(const T& initial) { store(initial); }
  SeqLock(const SeqLock&) = delete;
  SeqLock& operator=(const SeqLock&) = delete;

  /// Writer only.
  void write(const T& value) {
    const std::uint64_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    store(value);
    seq_.store(s + 2, std::memory_order_release);
  }

  /// Any thread: a consistent copy of the last written value.
  T read() const {
    Words words;
    for (;;) {
      const std::uint64_t s1 = seq_.load(std::memory_order_acquire);
      if ((s1 & 1u) != 0) continue;
      for (std::size_t i = 0; i < kWords; ++i) {
        words[i] = data_[i].load(std::memory_order_relaxed);
      }
      std::atomic_thread_fence(std::memory_order_acquire);
      const std::uint64_t s2 = seq_.load(std::memory_order_relaxed);
      if (s1 == s2) break;
    }
    T out;
    std::memcpy(&out, words, sizeof(T));
    return out;
  }

  /// Number of completed writes (for tests and change detection).
  std::uint64_t version() const { return seq_.load(std::memory_order_acquire) / 2; }

 private:
  static constexpr std::size_t kWords = (sizeof(T) + 7) / 8;
  using Words = std::uint64_t[kWords];

  void store(const T& value) {
    Words words = {};
    std::memcpy(words, &value, sizeof(T));
    for (std::size_t i = 0; i < kWords; ++i) data_[i].store(words[i], std::memory_order_relaxed);
  }

  std::atomic<std::uint64_t> seq_{0};
  std::atomic<std::uint64_t> data_[kWords];
};

}  // namespace vmass::runtime
