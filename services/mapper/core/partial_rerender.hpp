#pragma once
// A re-render that costs what changed: after keyframes moved, only the tiles their observations leave
// or enter are drawn again, from the stored observations that touch those tiles, in insertion order.
//
//  1. plan_rerender (the loop, from the FootprintIndex): a keyframe moved when some point of its
//     observations moves by more than min_shift_cells between the correction it is drawn with and
//     its current one (the largest move over the corners of its box: a rigid motion moves no point
//     of a box farther than a corner). The tiles under its old box and its new one are redrawn; every
//     keyframe (and run of keyframe-0 rows) whose box touches those tiles is replayed.
//  2. render_tiles (the worker, its own store connection): the tiles start as a full rebuild starts
//     (the compacted baseline's cells there, the prior; unknown elsewhere);
//     the replayed keyframes' rows are read by keyframe (an index of the store), sorted by row and
//     drawn into the tiles only (TileCanvas), each with its keyframe's correction.
//  3. The loop draws the observations it kept aside meanwhile into the same tiles, copies them into
//     the grid (OccupancyGrid::redraw: classes, inflation and dirty tiles follow) and records the new
//     corrections and boxes in the index (Mapper, mapper_rerender.cpp).
// Clamped log-odds depend on the order of updates, and each tile gets every update that touches it
// in the original order: the tiles equal a full rebuild's cell for cell. A keyframe moved by less
// than min_shift_cells stays drawn where it was (it is redrawn once its moves add up to more).
// A full rebuild instead: a keyframe drawn with several corrections, a move that leaves the grid (it
// would grow), or more than max_tile_fraction of the tiles to redraw (a full rebuild is then cheaper).
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "mapper/core/corrections.hpp"
#include "mapper/core/footprint_index.hpp"
#include "mapper/core/grid_config.hpp"
#include "mapper/core/observation_store.hpp"
#include "mapper/core/occupancy_grid.hpp"
#include "mapper/core/rerender_options.hpp"
#include "mapper/core/tile_canvas.hpp"

namespace slam::mapper {

// What a partial re-render draws, planned on the loop against the grid's current layout.
struct RerenderPlan {
  // One group of the index to replay into the tiles, with the correction to draw it with.
  struct Replay {
    KeyframeId keyframe = 0;
    int64_t first_row = 0;
    int64_t last_row = 0;
    Pose pose;
    uint32_t group = 0;  // its slot in the FootprintIndex
    bool moved = false;  // drawn with `pose` from now on (its box is measured as it is drawn)
  };
  GridGeometry geometry;
  GridConfig config;
  uint32_t layout_version = 0;  // the grid's when planned: the tiles apply to that layout only
  std::vector<uint32_t> tiles;  // ascending tile numbers (TileLayout of geometry, kGridTileSide)
  std::vector<Replay> replays;
  size_t moved = 0;  // keyframes moved by more than min_shift_cells
};

struct RerenderDecision {
  enum class Kind { Nothing, Partial, Full };
  Kind kind = Kind::Nothing;
  RerenderPlan plan;   // Partial
  std::string reason;  // Full: why
};

RerenderDecision plan_rerender(const FootprintIndex& index, const KeyframeCorrections& corrections,
                               const OccupancyGrid& grid, const RerenderOptions& options);

// The worker's result: the tiles drawn afresh, and what the index learns from it.
struct TileRender {
  RerenderPlan plan;
  TileCanvas canvas;
  std::vector<MapBox> boxes;  // per replay: where a moved one's observations are drawn now
  bool outside_grid = false;  // an observation would leave the grid: only a full rebuild is exact
  int64_t replayed = 0;       // observations drawn into the tiles
  int64_t rows_read = 0;      // rows read from the store (the replayed ones, and those touching no tile)
  int64_t rejected = 0;       // refused as a full rebuild refuses them
};

// Draws `plan`'s tiles from the store. Errors: the store cannot be read.
Result<TileRender> render_tiles(RerenderPlan plan, ObservationStore& store);

// Once the tiles are in the grid: the moved groups are drawn with their new corrections, over their
// new boxes (moved at `stamp_ns`, the newest stamp stored: a compaction leaves recent movers alone).
void record_redraw(const TileRender& render, FootprintIndex& index, int64_t stamp_ns = 0);

}  // namespace slam::mapper
