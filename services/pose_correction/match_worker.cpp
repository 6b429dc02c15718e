#include "pose_correction/match_worker.hpp"

#include <utility>

namespace slam::correction {

MatchWorker::MatchWorker(const MatcherOptions& options, Work work)
    : matcher_(options), work_(std::move(work)), thread_([this] { run(); }) {}

MatchWorker::~MatchWorker() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void MatchWorker::submit(std::unique_ptr<MatchJob> job) {
  {
    const std::lock_guard lock(mutex_);
    waiting_.push_back(std::move(job));
  }
  wake_.notify_one();
}

void MatchWorker::take_done(std::vector<std::unique_ptr<MatchJob>>& out) {
  const std::lock_guard lock(mutex_);
  for (auto& job : done_) out.push_back(std::move(job));
  done_.clear();
}

void MatchWorker::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || !waiting_.empty(); });
    if (stop_) return;
    std::unique_ptr<MatchJob> job = std::move(waiting_.front());
    waiting_.pop_front();
    lock.unlock();
    work_(matcher_, *job);  // touches nothing but the job and this thread's matcher
    lock.lock();
    done_.push_back(std::move(job));
  }
}

}  // namespace slam::correction
