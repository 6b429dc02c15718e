#pragma once
// IDL <-> core conversions for slam-mapper: observations in, grid requests in, snapshots and patches
// out. The only place where map.idl / robot.idl types meet the core's types.
#include <slam/fastdds/correction.h>
#include <slam/fastdds/map.h>
#include <slam/fastdds/robot.h>

#include <cstdint>
#include <vector>

#include "common/core/result.hpp"
#include "mapper/core/mapper.hpp"
#include "mapper/core/occupancy_grid.hpp"
#include "pose_correction/pose_corrector.hpp"

namespace slam::mapper {

// More points than this in one observation is corrupt input (a 360-beam scan has 360).
inline constexpr size_t kMaxPointsPerObservation = 65536;

// The grid's view of an observation; points are copied into the caller's reused buffers. Errors:
// empty robot id, too many points (NaN/Inf and range are the grid's to judge).
Result<ObservationView> to_view(const slam::RobotObservation& in, std::vector<Vec2>& hits,
                                std::vector<Vec2>& misses);

// Requests as the Mapper takes them (enum values outside the IDL's pass through, to be refused there).
LayoutRequest to_request(const slam::GridConfig& in);
EditRequest to_request(const slam::MapEdit& in);
FileRequest to_request(const slam::MapFileRequest& in);
slam::MapReply to_reply(const RequestReply& in);

void fill_correction(const correction::RobotCorrection& in, int64_t stamp_ns, slam::PoseCorrection* out);

void fill_snapshot(const OccupancyGrid& grid, uint32_t layout_id, uint64_t version, int64_t stamp_ns,
                   slam::GridSnapshot* out);
// The grid's dirty tiles as a patch; `encoded` is the caller's reused buffer.
void fill_patch(const OccupancyGrid& grid, uint32_t layout_id, uint64_t version, int64_t stamp_ns,
                EncodedTiles& encoded, slam::GridTiles* out);

}  // namespace slam::mapper
