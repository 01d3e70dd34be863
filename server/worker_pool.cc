#include "server/worker_pool.h"

#include "server/thread_priority.h"

namespace orbit::server {

WorkerPool::WorkerPool(int threads, int nice, int max_queued_calls)
    : max_queued_calls_(max_queued_calls) {
  threads_.reserve(threads);
  for (int i = 0; i < threads; ++i) {
    threads_.emplace_back([this, nice] {
      LowerThisThreadsPriority(nice);
      Run();
    });
  }
}

WorkerPool::~WorkerPool() {
  Stop();
  for (std::thread& t : threads_) t.join();
}

void WorkerPool::Post(Task task) {
  {
    MutexLock lock(&mutex_);
    if (!stopping_) {
      stream_work_.push_back(std::move(task));
      task.abandon = nullptr;
    }
  }
  if (task.abandon) {
    task.abandon();
    return;
  }
  wake_.Signal();
}

bool WorkerPool::TryPost(Task task) {
  {
    MutexLock lock(&mutex_);
    if (!stopping_) {
      if (static_cast<int>(calls_.size()) >= max_queued_calls_) return false;
      calls_.push_back(std::move(task));
      task.abandon = nullptr;
    }
  }
  if (task.abandon) {
    task.abandon();
    return true;
  }
  wake_.Signal();
  return true;
}

void WorkerPool::Stop() {
  std::deque<Task> abandoned;
  {
    MutexLock lock(&mutex_);
    stopping_ = true;
    abandoned = std::move(stream_work_);
    for (Task& call : calls_) abandoned.push_back(std::move(call));
    stream_work_.clear();
    calls_.clear();
  }
  wake_.SignalAll();
  for (Task& task : abandoned) task.abandon();
}

int WorkerPool::queued() const {
  MutexLock lock(&mutex_);
  return static_cast<int>(stream_work_.size() + calls_.size());
}

void WorkerPool::Run() {
  for (;;) {
    Task task;
    {
      MutexLock lock(&mutex_);
      while (!stopping_ && stream_work_.empty() && calls_.empty()) wake_.Wait(&mutex_);
      if (stopping_) return;  // Stop() abandoned what was queued
      std::deque<Task>& queue = stream_work_.empty() ? calls_ : stream_work_;
      task = std::move(queue.front());
      queue.pop_front();
    }
    task.run();
  }
}

}  // namespace orbit::server
