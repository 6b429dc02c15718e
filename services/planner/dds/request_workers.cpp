// RequestWorkers: a bounded queue of path requests drained by a few planner threads.
#include "planner/dds/request_workers.hpp"

#include <string>
#include <utility>

namespace slam::planner {

namespace {

PlanResult refused(std::string reason) {
  PlanResult r;
  r.status = PlanStatus::Timeout;
  r.reason = std::move(reason);
  return r;
}

}  // namespace

RequestWorkers::RequestWorkers(const PlannerConfig& config, uint32_t threads, size_t queue_limit, Reply reply)
    : reply_(std::move(reply)), queue_limit_(queue_limit), grid_(std::make_shared<const PlanningGrid>()) {
  for (uint32_t i = 0; i < threads; ++i) planners_.push_back(std::make_unique<PathPlanner>(config));
  for (auto& planner : planners_) threads_.emplace_back([this, p = planner.get()] { run(*p); });
}

RequestWorkers::~RequestWorkers() {
  std::deque<PathJob> left;
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
    left.swap(queue_);
  }
  wake_.notify_all();
  for (const PathJob& job : left) reply_(job, refused("planner is shutting down"));
  for (auto& t : threads_) t.join();
}

void RequestWorkers::set_grid(std::shared_ptr<const PlanningGrid> grid) {
  std::lock_guard lock(mutex_);
  grid_ = std::move(grid);
}

bool RequestWorkers::submit(PathJob job) {
  size_t queued = 0;
  {
    std::lock_guard lock(mutex_);
    queued = queue_.size();
    if (queued < queue_limit_) {
      queue_.push_back(std::move(job));
      wake_.notify_one();
      return true;
    }
  }
  reply_(job, refused("planner busy: " + std::to_string(queued) + " path requests already queued"));
  return false;
}

void RequestWorkers::run(PathPlanner& planner) {
  for (;;) {
    PathJob job;
    std::shared_ptr<const PlanningGrid> grid;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      job = std::move(queue_.front());
      queue_.pop_front();
      grid = grid_;
    }
    reply_(job, planner.plan(*grid, job.query));
  }
}

}  // namespace slam::planner
