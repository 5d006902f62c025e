// WorkerPool: every task runs exactly once per run(), task k on thread k % threads() (thread 0 the
// caller), run() returns only when every task is done, the pool is reused across runs, and a pool
// of fewer than one thread is refused.
#include "tensormass/kernels/worker_pool.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace tmlab::tm {
namespace {

TEST(WorkerPool, RunsEveryTaskOnceOnItsThreadAndWaitsForAll) {
  for (int threads : {1, 2, 3}) {
    WorkerPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (int n : {0, 1, 2, 7, 64}) {
      std::vector<std::atomic<int>> calls(static_cast<std::size_t>(n));
      std::vector<std::thread::id> ran_on(static_cast<std::size_t>(n));
      pool.run(n, [&](int k) {
        if (k == n - 1) std::this_thread::sleep_for(std::chrono::milliseconds(5));  // run() must wait
        ran_on[static_cast<std::size_t>(k)] = std::this_thread::get_id();
        calls[static_cast<std::size_t>(k)].fetch_add(1);
      });
      for (int k = 0; k < n; ++k) {
        EXPECT_EQ(calls[static_cast<std::size_t>(k)].load(), 1)
            << threads << " threads, task " << k << " of " << n;
        // thread k % threads(): tasks of one residue share a thread; residue 0 is the caller
        const auto& first = ran_on[static_cast<std::size_t>(k % threads)];
        EXPECT_EQ(ran_on[static_cast<std::size_t>(k)], first) << threads << " threads, task " << k;
        const bool on_caller = k % threads == 0 || n <= 1;
        EXPECT_EQ(ran_on[static_cast<std::size_t>(k)] == std::this_thread::get_id(), on_caller)
            << threads << " threads, task " << k;
      }
    }
  }
}

TEST(WorkerPool, IsReusedAcrossManyRuns) {
  WorkerPool pool(2);
  std::atomic<long> sum{0};
  for (int r = 0; r < 2000; ++r) pool.run(4, [&](int k) { sum.fetch_add(k + 1); });
  EXPECT_EQ(sum.load(), 2000L * 10);
}

TEST(WorkerPool, RefusesFewerThanOneThread) {
  EXPECT_THROW(WorkerPool(0), Error);
  EXPECT_THROW(WorkerPool(-2), Error);
}

}  // namespace
}  // namespace tmlab::tm
