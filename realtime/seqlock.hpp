// A sequence lock for a small trivially copyable value: one writer, any number of readers, nobody
// waits on a mutex. The writer makes the sequence odd, writes, makes it even again; a reader copies
// the value and retries when the sequence was odd or changed meanwhile (a writer was active).
// Readers can only spin while a write of a few words is in progress, never behind a blocked
// thread: the writer never waits for anyone.
//
// The payload is stored as relaxed atomic 64-bit words, so concurrent reads and writes are not a
// data race in the C++ memory model (a plain memcpy would be one, even if the retry discarded it);
// the fences order the payload against the sequence (Boehm, "Can seqlocks get along with
// programming language memory models?", 2012).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace tmlab::rt {

template <class T>
class SeqLock {
 public:
  static_assert(std::is_trivially_copyable_v<T>, "SeqLock holds trivially copyable values only");
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free, "SeqLock needs lock-free 64-bit atomics");

  explicit SeqLock(const T& initial = T{}) { store(initial); }
  SeqLock(const SeqLock&) = delete;
  SeqLock& operator=(const SeqLock&) = delete;

  /// Writer (one thread at a time).
  void store(const T& value) {
    std::array<std::uint64_t, kWords> w{};
    std::memcpy(w.data(), &value, sizeof(T));
    const std::uint64_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);  // odd: write in progress
    std::atomic_thread_fence(std::memory_order_release);
    for (std::size_t i = 0; i < kWords; ++i) words_[i].store(w[i], std::memory_order_relaxed);
    seq_.store(s + 2, std::memory_order_release);
  }

  /// Reader: a consistent copy of the last stored value.
  T load() const {
    std::array<std::uint64_t, kWords> w{};
    std::uint64_t s0 = 0, s1 = 0;
    do {
      s0 = seq_.load(std::memory_order_acquire);
      for (std::size_t i = 0; i < kWords; ++i) w[i] = words_[i].load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      s1 = seq_.load(std::memory_order_relaxed);
    } while ((s0 & 1u) != 0 || s0 != s1);
    T out;
    std::memcpy(static_cast<void*>(&out), w.data(), sizeof(T));  // T is trivially copyable
    return out;
  }

  /// Number of completed stores.
  std::uint64_t version() const { return seq_.load(std::memory_order_acquire) / 2; }

  static constexpr bool lock_free() { return std::atomic<std::uint64_t>::is_always_lock_free; }

 private:
  static constexpr std::size_t kWords = (sizeof(T) + 7) / 8;
  alignas(64) std::atomic<std::uint64_t> seq_{0};
  std::array<std::atomic<std::uint64_t>, kWords> words_{};
};

}  // namespace tmlab::rt
