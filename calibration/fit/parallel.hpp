// Runs f(0), ..., f(n-1) on up to `threads` std::threads (item i on thread i % threads). Each call
// writes only its own output slot, so results do not depend on the thread count. The first
// exception thrown by any call is rethrown after every thread has joined.
#pragma once

#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tmlab::fit {

template <class F>
void parallel_for(std::size_t n, int threads, F&& f) {
  const std::size_t t =
      std::max<std::size_t>(1, std::min<std::size_t>(n, std::size_t(threads > 0 ? threads : 1)));
  if (t <= 1) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  std::exception_ptr error;
  std::mutex m;
  std::vector<std::thread> pool;
  for (std::size_t w = 0; w < t; ++w)
    pool.emplace_back([&, w] {
      for (std::size_t i = w; i < n; i += t) {
        try {
          f(i);
        } catch (...) {
          std::lock_guard<std::mutex> lock(m);
          if (!error) error = std::current_exception();
        }
      }
    });
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace tmlab::fit
