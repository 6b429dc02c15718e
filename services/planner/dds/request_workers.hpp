#pragma once
// Answers one-off path requests on their own threads, so a long OMPL query never stalls goal
// ticks and waypoint streaming. Each thread owns a PathPlanner; all read the latest grid the loop
// handed over (immutable, shared). Every queued request is answered, even at shutdown.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "planner/core/path_planner.hpp"
#include "planner/core/planning_grid.hpp"
#include "planner/dds/planner_msgs.hpp"

namespace slam::planner {

class RequestWorkers {
 public:
  // Called on a worker thread (or the submitting thread when refused) with each answer.
  using Reply = std::function<void(const PathJob&, const PlanResult&)>;

  RequestWorkers(const PlannerConfig& config, uint32_t threads, size_t queue_limit, Reply reply);
  // Queued jobs are answered TIMEOUT ("shutting down"); running ones finish within their budget.
  ~RequestWorkers();
  RequestWorkers(const RequestWorkers&) = delete;
  RequestWorkers& operator=(const RequestWorkers&) = delete;

  // The grid queries starting from now on use.
  void set_grid(std::shared_ptr<const PlanningGrid> grid);
  // Queues the job; when the queue is full it is answered TIMEOUT at once and false returned.
  bool submit(PathJob job);

 private:
  void run(PathPlanner& planner);

  Reply reply_;
  size_t queue_limit_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::deque<PathJob> queue_;
  std::shared_ptr<const PlanningGrid> grid_;
  std::vector<std::unique_ptr<PathPlanner>> planners_;
  std::vector<std::thread> threads_;
};

}  // namespace slam::planner
