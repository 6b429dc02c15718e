// RebuildWorker: one thread per rebuild, its own store connection, the result handed back under a lock.
#include "mapper/core/rebuild_worker.hpp"

#include <exception>
#include <utility>

namespace slam::mapper {
namespace {

RebuildOutcome run(const GridConfig& config, const std::filesystem::path& path,
                   const KeyframeCorrections& corrections) {
  const auto start = std::chrono::steady_clock::now();
  RebuildStats stats;
  auto store = ObservationStore::open(path);
  FootprintIndex index;
  Result<OccupancyGrid> grid = store ? rebuild_grid(config, *store, &stats, corrections, &index)
                                     : Result<OccupancyGrid>(Error{store.message()});
  const auto took =
      std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start);
  return RebuildOutcome{std::move(grid),  std::move(stats), took,
                        std::move(index), std::nullopt,     std::nullopt};
}

RebuildOutcome run_partial(RerenderPlan plan, const std::filesystem::path& path) {
  const auto start = std::chrono::steady_clock::now();
  auto store = ObservationStore::open(path);
  RebuildOutcome outcome;
  outcome.partial =
      store ? render_tiles(std::move(plan), *store) : Result<TileRender>(Error{store.message()});
  outcome.took =
      std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start);
  return outcome;
}

RebuildOutcome run_compaction(const GridConfig& config, const std::filesystem::path& path,
                              const KeyframeCorrections& corrections, int64_t through_row) {
  const auto start = std::chrono::steady_clock::now();
  auto store = ObservationStore::open(path);
  RebuildOutcome outcome;
  outcome.compaction = store ? compact_store(config, *store, corrections, through_row)
                             : Result<CompactionReport>(Error{store.message()});
  outcome.took =
      std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start);
  return outcome;
}

}  // namespace

RebuildWorker::~RebuildWorker() {
  if (thread_.joinable()) thread_.join();
}

Status RebuildWorker::start(const GridConfig& config, const std::filesystem::path& path,
                            KeyframeCorrections corrections) {
  return launch(
      [config, path, corrections = std::move(corrections)] { return run(config, path, corrections); });
}

Status RebuildWorker::start_partial(RerenderPlan plan, const std::filesystem::path& path) {
  return launch([plan = std::move(plan), path]() mutable { return run_partial(std::move(plan), path); });
}

Status RebuildWorker::start_compaction(const GridConfig& config, const std::filesystem::path& path,
                                       KeyframeCorrections corrections, int64_t through_row) {
  return launch([config, path, corrections = std::move(corrections), through_row] {
    return run_compaction(config, path, corrections, through_row);
  });
}

Status RebuildWorker::launch(std::function<RebuildOutcome()> job) {
  std::lock_guard lock(mutex_);
  if (running_ || result_) return Error{"a rebuild is already running"};
  if (thread_.joinable()) thread_.join();  // the previous one has finished (its result was taken)
  running_ = true;
  try {
    thread_ = std::thread([this, job = std::move(job)] {
      std::optional<RebuildOutcome> outcome;
      try {
        outcome.emplace(job());
      } catch (const std::exception& e) {  // allocation failure on a huge layout, mostly
        outcome.emplace();
        outcome->grid = Error{std::string("rebuild failed: ") + e.what()};
      }
      {
        std::lock_guard done(mutex_);
        result_ = std::move(outcome);
        running_ = false;
      }
      if (on_done_) on_done_();
    });
  } catch (const std::exception& e) {
    running_ = false;
    return Error{std::string("cannot start the rebuild thread: ") + e.what()};
  }
  return Status::ok();
}

bool RebuildWorker::busy() const {
  std::lock_guard lock(mutex_);
  return running_ || result_.has_value();
}

std::optional<RebuildOutcome> RebuildWorker::take() {
  std::lock_guard lock(mutex_);
  if (running_) return std::nullopt;
  return std::exchange(result_, std::nullopt);
}

std::optional<RebuildOutcome> RebuildWorker::wait() {
  if (thread_.joinable()) thread_.join();
  return take();
}

}  // namespace slam::mapper
