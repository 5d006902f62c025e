#include "tensormass/kernels/worker_pool.hpp"

#include "core/base/error.hpp"

#include <string>

namespace tmlab::tm {

WorkerPool::WorkerPool(int threads) : threads_(threads) {
  if (threads < 1) throw Error("worker pool: threads = " + std::to_string(threads) + " must be >= 1");
  workers_.reserve(static_cast<std::size_t>(threads - 1));
  for (int id = 1; id < threads; ++id) workers_.emplace_back([this, id] { work(id); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
  }
  start_.notify_all();
  for (auto& w : workers_) w.join();
}

void WorkerPool::work(int id) {
  long seen = 0;
  for (;;) {
    const std::function<void(int)>* fn = nullptr;
    int n = 0;
    {
      std::unique_lock<std::mutex> lock(m_);
      start_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      fn = fn_;
      n = n_tasks_;
    }
    for (int k = id; k < n; k += threads_) (*fn)(k);
    {
      std::lock_guard<std::mutex> lock(m_);
      if (--busy_ == 0) done_.notify_one();
    }
  }
}

void WorkerPool::run(int n_tasks, const std::function<void(int)>& fn) {
  if (threads_ == 1 || n_tasks <= 1) {
    for (int k = 0; k < n_tasks; ++k) fn(k);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(m_);
    fn_ = &fn;
    n_tasks_ = n_tasks;
    busy_ = threads_ - 1;
    ++generation_;
  }
  start_.notify_all();
  for (int k = 0; k < n_tasks; k += threads_) fn(k);
  std::unique_lock<std::mutex> lock(m_);
  done_.wait(lock, [&] { return busy_ == 0; });
  fn_ = nullptr;
}

}  // namespace tmlab::tm
