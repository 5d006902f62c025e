// WorkerPool: a fixed set of threads started once (at construction) and reused by every kernel call,
// so a force evaluation pays a wake-up, never a thread start. Owned by the model that uses it (no
// global pool). run(n, fn) executes fn(task) for task = 0..n-1: task k on thread k % threads(),
// thread 0 being the caller; it returns when every task is done. The kernels give each task
// disjoint output, so which thread runs a task never changes a result.
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tmlab::tm {

class WorkerPool {
 public:
  /// threads >= 1 (throws tmlab::Error otherwise); starts threads - 1 workers.
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return threads_; }
  /// fn(task) for task = 0..n_tasks-1 (task k on thread k % threads()). fn must not throw.
  void run(int n_tasks, const std::function<void(int)>& fn);

 private:
  void work(int id);

  int threads_ = 1;
  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable start_, done_;
  const std::function<void(int)>* fn_ = nullptr;
  int n_tasks_ = 0;
  long generation_ = 0;
  int busy_ = 0;
  bool stop_ = false;
};

}  // namespace tmlab::tm
