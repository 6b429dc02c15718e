#include "pose_correction/graph_optimizer.hpp"

#include <exception>
#include <string>
#include <utility>

namespace slam::correction {

GraphOptimizer::GraphOptimizer() : worker_([this] { run(); }) {}

GraphOptimizer::~GraphOptimizer() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  cancel_.store(true);
  work_ready_.notify_all();
  worker_.join();
}

uint64_t GraphOptimizer::submit(PoseGraph graph, const OptimiseOptions& options) {
  uint64_t id = 0;
  {
    const std::lock_guard lock(mutex_);
    id = next_job_++;
    ++counters_.submitted;
    if (pending_) ++counters_.coalesced;
    pending_.emplace(Job{id, std::move(graph), options});
  }
  work_ready_.notify_one();
  return id;
}

bool GraphOptimizer::poll() const {
  const std::lock_guard lock(mutex_);
  return result_.has_value();
}

std::optional<OptimisationResult> GraphOptimizer::take_result() {
  const std::lock_guard lock(mutex_);
  return std::exchange(result_, std::nullopt);
}

bool GraphOptimizer::wait_idle(std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  return idle_.wait_for(lock, timeout, [this] { return !pending_ && !running_; });
}

OptimizerCounters GraphOptimizer::counters() const {
  const std::lock_guard lock(mutex_);
  return counters_;
}

void GraphOptimizer::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    work_ready_.wait(lock, [this] { return stopping_ || pending_.has_value(); });
    if (stopping_) return;
    Job job = std::move(*pending_);
    pending_.reset();
    running_ = true;
    ++counters_.started;
    lock.unlock();
    OptimisationResult result = solve(job);
    lock.lock();
    running_ = false;
    ++counters_.solved;
    if (!result.status) ++counters_.failed;
    result_ = std::move(result);
    idle_.notify_all();
  }
}

OptimisationResult GraphOptimizer::solve(Job& job) const {
  OptimisationResult result;
  result.job = job.id;
  job.options.cancel = &cancel_;
  // Ceres reports its failures in the summary; what it may still throw (allocation) becomes a
  // failed result instead of ending the process.
  try {
    auto stats = job.graph.optimise(job.options);
    if (!stats) {
      result.status = stats.error();
      return result;
    }
    result.stats = *stats;
    result.estimates = job.graph.estimates();
  } catch (const std::exception& e) {
    result.status = Error{std::string{"pose graph optimisation threw: "} + e.what()};
  } catch (...) {
    result.status = Error{"pose graph optimisation threw a non-standard exception"};
  }
  return result;
}

}  // namespace slam::correction
