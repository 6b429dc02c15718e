#pragma once
// Conversions between the gateway core and the generated DDS types, in one place. Samples are
// filled in place so the caller's reused sample keeps its sequence capacity between messages.
#include <slam/fastdds/correction.h>
#include <slam/fastdds/mqtt.h>
#include <slam/fastdds/nav.h>
#include <slam/fastdds/robot.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fastrtps/utils/fixed_size_string.hpp>
#include <span>
#include <string_view>
#include <vector>

#include "common/core/bounded_text.hpp"
#include "gateway/core/fleet_digest.hpp"
#include "gateway/core/frame_correction.hpp"
#include "gateway/core/gateway_intake.hpp"
#include "gateway/core/robot_registry.hpp"
#include "gateway/core/traffic_queue.hpp"
#include "protocol/codec_types.hpp"

namespace slam::gateway {

// Sets a bounded DDS string from `text`, cut to N bytes at a character boundary. (fixed_string::assign
// does not write the terminating NUL, so a shorter value would keep the tail of a longer one: go
// through a C string.)
template <std::size_t N>
void set_text(eprosima::fastrtps::fixed_string<N>& out, std::string_view text) {
  char buffer[N + 1];
  const std::string_view cut = bounded_prefix(text, N);
  std::memcpy(buffer, cut.data(), cut.size());
  buffer[cut.size()] = '\0';
  out = static_cast<const char*>(buffer);
}

template <std::size_t N>
std::string_view text_of(const eprosima::fastrtps::fixed_string<N>& s) {
  return {s.c_str(), s.size()};
}

// A new last element of `batch`, taken from `spare` when it has one (its point buffers reused).
slam::RobotObservation& append_observation(slam::RobotObservationBatch& batch,
                                           std::vector<slam::RobotObservation>& spare);
// Moves the written batch's elements to `spare`, leaving the batch empty.
void recycle_observations(slam::RobotObservationBatch& batch, std::vector<slam::RobotObservation>& spare);
void fill_observation(std::string_view robot_id, std::uint64_t seq, std::int64_t stamp_ns, Protocol protocol,
                      const protocol::DecodedObservation& in, slam::RobotObservation& out);
// The robot's state with `map_pose` (its reported pose in the map frame).
void fill_state(const RobotRecord& in, const Pose& map_pose, slam::RobotState& out);
// The robot's pose as it reported it, and the correction version `fill_state` was given a pose for.
void fill_odometry(const RobotRecord& in, std::uint64_t correction_version, slam::RobotOdometry& out);
// A PoseCorrection sample as the gateway keeps it.
Correction to_correction(const slam::PoseCorrection& in);
// The readers' samples as the loop takes them from the intake.
CorrectionInput to_input(const slam::PoseCorrection& in);
WaypointInput to_input(const slam::WaypointCommand& in);
MqttRequestInput to_input(const slam::MqttRequest& in);
ProtocolReport to_input(const slam::RobotState& in);
void fill_traffic(const TrafficRecord& in, slam::MqttTraffic& out);
// A fleet digest of gateway `gateway_id` (robots already placed in the map frame).
void fill_digest(std::string_view gateway_id, std::int64_t stamp_ns, std::span<const DigestRobotEntry> robots,
                 slam::FleetDigest& out);
void fill_points(std::string_view gateway_id, std::int64_t stamp_ns,
                 std::span<const DigestPointsEntry> robots, slam::FleetPoints& out);
// DDS points into `out` (replaced, capacity kept).
void to_points(const std::vector<slam::Point2>& in, std::vector<protocol::Point>& out);

}  // namespace slam::gateway
