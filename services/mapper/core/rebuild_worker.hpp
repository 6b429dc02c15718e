#pragma once
// Rebuilds off the map loop: a layout change, a robot reset or a full re-render with new keyframe
// corrections replays the whole store, which may take seconds, while the loop keeps integrating and
// publishing with the current grid; a partial re-render draws a few tiles (partial_rerender.hpp). The worker
// reads through its own SQLite connection (WAL lets it read while the loop's connection stays open) and the
// loop swaps the finished grid in; a compaction (compaction.hpp) writes the baseline through it too. One job
// at a time.
#include <chrono>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "common/core/result.hpp"
#include "mapper/core/compaction.hpp"
#include "mapper/core/corrections.hpp"
#include "mapper/core/grid_config.hpp"
#include "mapper/core/observation_store.hpp"
#include "mapper/core/occupancy_grid.hpp"
#include "mapper/core/partial_rerender.hpp"
#include "mapper/core/rebuild.hpp"

namespace slam::mapper {

struct RebuildOutcome {
  Result<OccupancyGrid> grid = Error{"a partial re-render draws tiles, not a grid"};
  RebuildStats stats;
  std::chrono::milliseconds took{0};
  FootprintIndex index;                                // a full rebuild's: where it drew each observation
  std::optional<Result<TileRender>> partial;           // set by start_partial (then `grid` is not used)
  std::optional<Result<CompactionReport>> compaction;  // set by start_compaction (likewise)
};

class RebuildWorker {
 public:
  // `on_done` runs on the worker thread when a result is ready (e.g. to wake the loop); keep it short.
  explicit RebuildWorker(std::function<void()> on_done) : on_done_(std::move(on_done)) {}
  ~RebuildWorker();  // waits for a running rebuild
  RebuildWorker(const RebuildWorker&) = delete;
  RebuildWorker& operator=(const RebuildWorker&) = delete;

  // Starts rebuilding `config` from the store at `path`, each observation moved by its keyframe's
  // correction (a re-render is a rebuild with the current config and new corrections). The caller
  // must not append observations until the result is taken (the rebuild must see exactly what was
  // committed when it started).
  Status start(const GridConfig& config, const std::filesystem::path& path,
               KeyframeCorrections corrections = {});
  // Starts drawing a partial re-render's tiles from the store at `path` (same rule: nothing appended
  // until the result is taken).
  Status start_partial(RerenderPlan plan, const std::filesystem::path& path);
  // Starts compacting the rows up to `through_row` of the store at `path` (compaction.hpp; same rule,
  // and the loop's connection must hold no open batch: this one writes).
  Status start_compaction(const GridConfig& config, const std::filesystem::path& path,
                          KeyframeCorrections corrections, int64_t through_row);
  bool busy() const;
  // The finished rebuild, once; nullopt while running or idle.
  std::optional<RebuildOutcome> take();
  // Blocks until a running rebuild finishes, then returns it (nullopt when idle).
  std::optional<RebuildOutcome> wait();

 private:
  Status launch(std::function<RebuildOutcome()> job);

  std::function<void()> on_done_;
  mutable std::mutex mutex_;
  bool running_ = false;
  std::optional<RebuildOutcome> result_;
  std::thread thread_;
};

}  // namespace slam::mapper
