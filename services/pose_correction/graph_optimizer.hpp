#pragma once
// Optimises pose graphs on a background thread so the mapper's loop never waits for Ceres: submit()
// hands over a snapshot and returns at once; a snapshot submitted while another is still waiting
// replaces it (only the newest graph is worth solving); take_result() hands back the newest finished
// solve. The destructor aborts a running solve at its next iteration and joins the thread.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "common/core/result.hpp"
#include "pose_correction/pose_graph.hpp"

namespace slam::correction {

struct OptimisationResult {
  uint64_t job = 0;                     // the submit() this answers
  Status status;                        // a failed solve: its message, and no estimates
  std::vector<NodeEstimate> estimates;  // every node of the submitted graph, optimised
  OptimiseStats stats;
};

struct OptimizerCounters {
  uint64_t submitted = 0;
  uint64_t coalesced = 0;  // submits replaced by a newer one before their solve started
  uint64_t started = 0;    // solves begun
  uint64_t solved = 0;     // solves finished, failed ones included
  uint64_t failed = 0;
};

class GraphOptimizer {
 public:
  GraphOptimizer();
  ~GraphOptimizer();
  GraphOptimizer(const GraphOptimizer&) = delete;
  GraphOptimizer& operator=(const GraphOptimizer&) = delete;

  // Queues `graph` for optimisation and returns its job number (1, 2, ...). Never blocks on a solve.
  // options.cancel is replaced by the optimiser's own (set by the destructor).
  uint64_t submit(PoseGraph graph, const OptimiseOptions& options = {});
  // Whether a finished result waits to be taken.
  bool poll() const;
  // The newest finished result (older unclaimed ones are dropped), or nullopt.
  std::optional<OptimisationResult> take_result();
  // Blocks until no job waits or runs, at most `timeout`; false on timeout.
  bool wait_idle(std::chrono::milliseconds timeout) const;
  OptimizerCounters counters() const;

 private:
  struct Job {
    uint64_t id = 0;
    PoseGraph graph;
    OptimiseOptions options;
  };

  void run();
  OptimisationResult solve(Job& job) const;

  mutable std::mutex mutex_;
  std::condition_variable work_ready_;
  mutable std::condition_variable idle_;
  std::optional<Job> pending_;
  std::optional<OptimisationResult> result_;
  bool running_ = false;
  bool stopping_ = false;
  uint64_t next_job_ = 1;
  OptimizerCounters counters_;
  std::atomic<bool> cancel_{false};
  std::thread worker_;  // last: starts after every member it uses exists
};

}  // namespace slam::correction
