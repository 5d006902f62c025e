// A single-producer / single-consumer triple buffer: the writer always owns one buffer, the reader
// one, and the third ("middle") is handed over through ONE atomic word, so neither side ever waits
// for the other, takes a lock or allocates.
//
// State word: bits 0-1 the index of the middle buffer, bit 2 "fresh" (the middle holds data the
// reader has not taken yet).
//   publish():  the writer swaps its back buffer with the middle and sets fresh
//               (exchange, release: the reader that takes it sees everything written before).
//   update():   when fresh is set the reader swaps its front buffer with the middle and clears fresh
//               (exchange, acquire). Without new data it keeps its front buffer.
// The reader therefore always sees the newest complete buffer; intermediate ones are dropped, which
// is what a display or a haptic loop wants. The buffers are built once from a prototype (so a
// buffer holding std::vector keeps its capacity: no allocation on the hot path).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

namespace tmlab::rt {

template <class T>
class TripleBuffer {
 public:
  static_assert(std::atomic<std::uint32_t>::is_always_lock_free, "the triple buffer needs a lock-free word");

  explicit TripleBuffer(const T& prototype = T{}) : buffers_{prototype, prototype, prototype} {}
  TripleBuffer(const TripleBuffer&) = delete;
  TripleBuffer& operator=(const TripleBuffer&) = delete;

  // ---- writer (one thread) ----
  /// The buffer the writer fills (stays the writer's until publish()).
  T& write_buffer() { return buffers_[back_]; }
  /// Hands the written buffer to the reader; the writer gets the old middle buffer to fill next.
  void publish() {
    const std::uint32_t old = state_.exchange(back_ | kFresh, std::memory_order_acq_rel);
    back_ = old & kIndex;
  }

  // ---- reader (one thread) ----
  /// Takes the newest published buffer if there is one; returns true when the front buffer changed.
  bool update() {
    if ((state_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    const std::uint32_t old = state_.exchange(front_, std::memory_order_acq_rel);
    front_ = old & kIndex;
    return true;
  }
  /// The reader's current buffer (the newest one at the last update()).
  const T& read_buffer() const { return buffers_[front_]; }

  /// True: the hand-over word is a lock-free atomic on this platform (the no-lock claim, tested).
  static constexpr bool lock_free() { return std::atomic<std::uint32_t>::is_always_lock_free; }

 private:
  static constexpr std::uint32_t kIndex = 3u, kFresh = 4u;
  std::array<T, 3> buffers_;
  // Writer owns back_, reader owns front_, the state word holds the middle; initially 0, 1, 2.
  std::uint32_t back_ = 0;
  std::uint32_t front_ = 1;
  alignas(64) std::atomic<std::uint32_t> state_{2};
};

}  // namespace tmlab::rt
