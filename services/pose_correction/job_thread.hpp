#pragma once
// One thread that runs units of work in submission order, off the mapper's loop: the loop submits a
// job that carries copies of everything its work reads, and takes it back, done, at a later pass.
// The work touches only the job (and whatever the work's owner gives this thread alone), so nothing
// is shared but the queues, which are locked only to move job pointers.
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace slam::correction {

template <typename Job>
class JobThread {
 public:
  using Work = std::function<void(Job&)>;
  // `on_done` (may be empty) runs on this thread after each job is done: to wake the loop.
  explicit JobThread(Work work, std::function<void()> on_done = {})
      : work_(std::move(work)), on_done_(std::move(on_done)), thread_([this] { run(); }) {}
  ~JobThread() {  // finishes the running job, drops the waiting ones
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }
  JobThread(const JobThread&) = delete;
  JobThread& operator=(const JobThread&) = delete;

  void submit(std::unique_ptr<Job> job) {
    {
      const std::lock_guard lock(mutex_);
      waiting_.push_back(std::move(job));
    }
    wake_.notify_one();
  }
  // Appends the finished jobs, in submission order.
  void take_done(std::vector<std::unique_ptr<Job>>& out) {
    const std::lock_guard lock(mutex_);
    for (auto& job : done_) out.push_back(std::move(job));
    done_.clear();
  }

 private:
  void run() {
    std::unique_lock lock(mutex_);
    while (true) {
      wake_.wait(lock, [this] { return stop_ || !waiting_.empty(); });
      if (stop_) return;
      std::unique_ptr<Job> job = std::move(waiting_.front());
      waiting_.pop_front();
      lock.unlock();
      work_(*job);
      lock.lock();
      done_.push_back(std::move(job));
      if (on_done_) {
        lock.unlock();
        on_done_();
        lock.lock();
      }
    }
  }

  Work work_;
  std::function<void()> on_done_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::unique_ptr<Job>> waiting_;
  std::vector<std::unique_ptr<Job>> done_;
  bool stop_ = false;
  std::thread thread_;  // last: starts once everything it uses exists
};

}  // namespace slam::correction
