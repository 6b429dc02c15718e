#pragma once
// Rebuilding the grid from the store: after a config change (resolution, extent, inflation, legacy
// mode), after a robot's data is reset, after a pose-graph optimisation moved keyframes (re-render),
// and at start-up to restore the map a restart left behind.
#include <cstdint>
#include <string>

#include "common/core/result.hpp"
#include "mapper/core/corrections.hpp"
#include "mapper/core/footprint_index.hpp"
#include "mapper/core/grid_config.hpp"
#include "mapper/core/observation_store.hpp"
#include "mapper/core/occupancy_grid.hpp"

namespace slam::mapper {

struct RebuildStats {
  int64_t observations = 0;    // integrated
  int64_t rejected = 0;        // refused by the new config (e.g. a smaller max_range_m)
  int64_t clipped = 0;         // hits past the new maximum extent
  int64_t obstructions = 0;    // manual obstructions re-applied
  int64_t prior_cells = 0;     // cells set from the stored prior
  int64_t baseline_cells = 0;  // cells set from the compacted baseline
  std::string first_error;     // the first rejection's reason, for the log
};

// A fresh grid with `config`: the compacted baseline (and the stored prior over it when imported
// after the compaction; without a baseline the prior alone), then every observation in insertion order moved
// into the map frame by its keyframe's correction (identity for keyframe 0 or ids `corrections` does not
// hold), then the manual obstructions. `index`, when given, is cleared and records where every
// integrated observation was drawn (a partial re-render starts from it). Errors: invalid config, or
// the store cannot be read; the caller keeps its current grid in that case.
Result<OccupancyGrid> rebuild_grid(const GridConfig& config, ObservationStore& store,
                                   RebuildStats* stats = nullptr, const KeyframeCorrections& corrections = {},
                                   FootprintIndex* index = nullptr);

// What every rebuild starts from (see rebuild_grid). Errors: the store cannot be read.
Status apply_stored_start(OccupancyGrid& grid, ObservationStore& store, RebuildStats& stats);

// rebuild_grid up to row `through_row` and without the obstructions (not log-odds): the state a
// compaction keeps as the new baseline.
Result<OccupancyGrid> rebuild_through(const GridConfig& config, ObservationStore& store, int64_t through_row,
                                      const KeyframeCorrections& corrections, RebuildStats* stats = nullptr);

}  // namespace slam::mapper
