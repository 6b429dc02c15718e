#pragma once
// IDL <-> core conversions for slam-mapper: observations in, grid requests in, snapshots and patches
// out. The only place where map.idl / robot.idl types meet the core's types.
#include <slam/fastdds/map.h>
#include <slam/fastdds/robot.h>

#include <cstdint>
#include <vector>

#include "common/core/result.hpp"
#include "mapper/grid_config.hpp"
#include "mapper/map_files.hpp"
#include "mapper/occupancy_grid.hpp"

namespace slam::mapper {

// More points than this in one observation is corrupt input (a 360-beam scan has 360).
inline constexpr size_t kMaxPointsPerObservation = 65536;

// The grid's view of an observation; points are copied into the caller's reused buffers. Errors:
// empty robot id, too many points (NaN/Inf and range are the grid's to judge).
Result<ObservationView> to_view(const slam::RobotObservation& in, std::vector<Vec2>& hits,
                                std::vector<Vec2>& misses);

// `current` with the fields a GridConfig request sets. width_m/height_m 0 and a negative
// inflation_radius keep the current values (what slamctl sends for "unchanged"). Validated: the
// error names the key.
Result<GridConfig> requested_config(const slam::GridConfig& request, const GridConfig& current);

void fill_snapshot(const OccupancyGrid& grid, uint32_t layout_id, uint64_t version, int64_t stamp_ns,
                   slam::GridSnapshot* out);
void fill_patch(const OccupancyGrid& grid, const CellBox& box, uint32_t layout_id, uint64_t version,
                int64_t stamp_ns, slam::GridPatch* out);

slam::MapResult to_map_result(FileFailure failure);

}  // namespace slam::mapper
