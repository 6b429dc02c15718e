#pragma once
// Compaction: the store stays bounded while the map still rebuilds exactly from it.
//
// A rebuild is a fold of every stored observation, in insertion order, over a start state. The state
// after row R is a grid of log-odds; kept as a baseline (store_baseline.hpp) in place of rows 1..R, a
// rebuild that starts from it and replays the rows after R ends where the whole fold ends, cell for
// cell (clamping and growth included: the baseline keeps the layout the fold had then). So a compaction
//  1. picks R on the loop (plan_compaction, from the FootprintIndex): every row up to R belongs to a
//     keyframe (or run of keyframe-0 rows) first observed at least `retention_days` ago (or, when the
//     store passes `max_mb`, `min_age_s` ago) and not moved for `min_age_s`; at least one row stays;
//  2. on the worker (compact_store, its own connection): replays the baseline and rows 1..R with the
//     current corrections, stores that grid's log-odds as the new baseline and deletes rows 1..R, in one
//     transaction;
//  3. on the loop: the FootprintIndex forgets those rows (FootprintIndex::drop_through).
// Compacted evidence is fixed where it was drawn: a compacted keyframe that moves later (a loop closure
// long after) moves only its remaining rows; its baked occupancy stays and new observations correct it
// (a saturated wall needs (clamp_max - occupied_threshold) / -miss = 11 scans that see through it,
// grid_config.hpp). New evidence thus outweighs old where they disagree, compacted or not.
// Plain C++ and SQLite; not thread-safe (the loop plans, the worker compacts).
#include <cstdint>
#include <optional>
#include <string>

#include "common/core/result.hpp"
#include "mapper/core/compaction_options.hpp"
#include "mapper/core/corrections.hpp"
#include "mapper/core/footprint_index.hpp"
#include "mapper/core/grid_config.hpp"
#include "mapper/core/observation_store.hpp"
#include "mapper/core/rebuild.hpp"

namespace slam::mapper {

struct CompactionPlan {
  int64_t through_row = 0;  // compact rows 1..through_row
  size_t groups = 0;        // index groups it removes whole
  std::string why;          // for the log
};

// What to compact now (nullopt: nothing). Ages are measured on the gateway stamps of the stored
// observations: `now_stamp_ns` is the newest stored, so a simulation at 8x ages 8x too.
// `last_global_move_ns`: when a full re-render last redrew everything (the index then forgets who moved).
// Something is due when a group of the index has rows up to the cut (a compaction drops them from it;
// row ids are not compared with the baseline's: a robot reset may delete the newest rows and SQLite
// then numbers new rows from the largest left).
std::optional<CompactionPlan> plan_compaction(const FootprintIndex& index, int64_t now_stamp_ns,
                                              int64_t used_bytes, int64_t last_global_move_ns,
                                              const CompactionOptions& options);

struct CompactionReport {
  int64_t through_row = 0;
  int64_t rows_deleted = 0;
  int64_t tiles = 0;   // baseline tiles now
  RebuildStats stats;  // of the replay through through_row
};

// Step 2 above. Errors: the store cannot be read or written (then nothing changed).
Result<CompactionReport> compact_store(const GridConfig& config, ObservationStore& store,
                                       const KeyframeCorrections& corrections, int64_t through_row);

}  // namespace slam::mapper
