// The lock-free hand-over of the real-time loop: the triple buffer and the sequence lock never
// tear a value under concurrent use, and their hand-over words are lock-free atomics (the "no
// lock on the hot path" claim: the types hold no mutex, and these static facts are checked here).
#include "realtime/seqlock.hpp"
#include "realtime/triple_buffer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace tmlab::rt {
namespace {

struct Triple {
  double a = 0.0, b = 0.0, c = 0.0;
  long n = 0;
};

TEST(LockFree, HandOverWordsAreLockFreeAtomics) {
  static_assert(TripleBuffer<std::vector<float>>::lock_free());
  static_assert(SeqLock<Triple>::lock_free());
  EXPECT_TRUE(std::atomic<std::uint32_t>{}.is_lock_free());
  EXPECT_TRUE(std::atomic<std::uint64_t>{}.is_lock_free());
}

TEST(LockFree, SeqLockNeverTearsAndReadsAreMonotone) {
  SeqLock<Triple> lock;
  constexpr long kWrites = 200000;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (long i = 1; i <= kWrites; ++i) lock.store({double(i), 2.0 * double(i), -double(i), i});
    done = true;
  });
  long last = 0, reads = 0;
  while (!done.load() || last < kWrites) {
    const Triple t = lock.load();
    ASSERT_EQ(t.b, 2.0 * t.a);
    ASSERT_EQ(t.c, -t.a);
    ASSERT_EQ(double(t.n), t.a);
    ASSERT_GE(t.n, last);
    last = t.n;
    ++reads;
  }
  writer.join();
  EXPECT_EQ(last, kWrites);
  EXPECT_EQ(lock.version(), std::uint64_t(kWrites) + 1);  // + the constructor's store
  EXPECT_GT(reads, 0);
}

TEST(LockFree, TripleBufferDeliversWholeBuffersInOrder) {
  // Each published buffer is filled with one value; the reader must only ever see uniform buffers,
  // never an older one after a newer one, and the last one eventually.
  TripleBuffer<std::vector<long>> buf(std::vector<long>(1000, 0));
  constexpr long kFrames = 50000;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (long i = 1; i <= kFrames; ++i) {
      std::vector<long>& w = buf.write_buffer();
      for (long& v : w) v = i;
      buf.publish();
    }
    done = true;
  });
  long last = 0;
  while (!(done.load() && last == kFrames)) {
    if (!buf.update()) continue;
    const std::vector<long>& r = buf.read_buffer();
    ASSERT_EQ(r.size(), 1000u);
    for (long v : r) ASSERT_EQ(v, r.front());
    ASSERT_GT(r.front(), last);
    last = r.front();
  }
  writer.join();
  EXPECT_EQ(last, kFrames);
  EXPECT_FALSE(buf.update());  // nothing new
}

TEST(LockFree, TripleBufferKeepsCapacity) {
  // Buffers are built from the prototype once: writing never reallocates them.
  TripleBuffer<std::vector<float>> buf(std::vector<float>(300, 0.0f));
  const float* p0 = buf.write_buffer().data();
  std::vector<const float*> seen{p0};
  for (int i = 0; i < 10; ++i) {
    buf.publish();
    buf.update();
    seen.push_back(buf.write_buffer().data());
    EXPECT_EQ(buf.write_buffer().size(), 300u);
  }
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  EXPECT_EQ(seen.size(), 3u);  // the same three buffers go round
}

}  // namespace
}  // namespace tmlab::rt
