// ROS 2 recordings (ros2_mcap_log.hpp).
#include "simulator/robot_log/ros2_mcap_log.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "simulator/robot_log/laser_mount.hpp"
#include "simulator/robot_log/odometry_track.hpp"
#include "simulator/robot_log/ros2_messages.hpp"

namespace slam::robot_log {

namespace {

bool has_type(const mcap::Contents& contents, const mcap::Channel& channel, std::string_view type) {
  const auto schema = contents.schemas.find(channel.schema_id);
  return channel.message_encoding == "cdr" && schema != contents.schemas.end() && schema->second.name == type;
}

// The channel of `type` on `topic`, or the only one of that type when `topic` is empty.
Result<uint16_t> pick_channel(const mcap::Contents& contents, std::string_view type,
                              const std::string& topic) {
  std::vector<const mcap::Channel*> found;
  for (const auto& [id, channel] : contents.channels)
    if (has_type(contents, channel, type)) found.push_back(&channel);
  std::string topics;
  for (const mcap::Channel* c : found) topics += (topics.empty() ? "" : ", ") + c->topic;
  if (!topic.empty()) {
    for (const mcap::Channel* c : found)
      if (c->topic == topic) return c->id;
    return Error{fmt::format("no {} topic '{}' in the recording (it has: {})", type, topic,
                             topics.empty() ? "none" : topics)};
  }
  if (found.empty()) return Error{fmt::format("the recording has no {} topic (with cdr messages)", type)};
  if (found.size() > 1)
    return Error{fmt::format("the recording has several {} topics ({}): choose one", type, topics)};
  return found.front()->id;
}

double yaw_of(const Quaternion& q) {
  return std::atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
}

// A scan waiting for the odometry around it.
struct PendingScan {
  uint64_t message = 0;  // 1-based, for the bad-line note
  Ros2LaserScan scan;
};

LaserScan to_laser_scan(Ros2LaserScan&& in, const Pose& odom, const std::optional<LaserMount>& mount) {
  LaserScan out;
  out.stamp_s = in.header.stamp_s;
  out.odom = odom;
  out.angle_min_rad = in.angle_min;
  out.angle_increment_rad = in.angle_increment;
  out.max_range_m = in.range_max;
  out.ranges = std::move(in.ranges);
  // Readings below range_min are invalid in ROS; 0 is "no return" here.
  for (float& r : out.ranges)
    if (r < in.range_min) r = 0;
  if (mount) {
    out.laser_in_robot = mount->in_robot;
    if (mount->mirrored && !out.ranges.empty()) {
      // Seen from above, beam i of an upside-down laser lies at -(angle_min + i * increment).
      const double last =
          out.angle_min_rad + out.angle_increment_rad * static_cast<double>(out.ranges.size() - 1);
      out.angle_min_rad = -last;
      std::reverse(out.ranges.begin(), out.ranges.end());
    }
  }
  return out;
}

}  // namespace

Status Ros2McapOptions::validate() const {
  if (!(max_odometry_gap_s > 0) || !std::isfinite(max_odometry_gap_s))
    return Error{fmt::format("max_odometry_gap_s must be finite and > 0, not {}", max_odometry_gap_s)};
  return Status::ok();
}

Result<RobotLog> ros2_log_from_mcap(const mcap::Contents& contents, const Ros2McapOptions& options) {
  SLAM_TRY(options.validate());
  auto scan_channel = pick_channel(contents, kLaserScanType, options.scan_topic);
  if (!scan_channel) return scan_channel.error();
  auto odom_channel = pick_channel(contents, kOdometryType, options.odom_topic);
  if (!odom_channel) return odom_channel.error();

  RobotLog log;
  LogStats& stats = log.stats;
  uint64_t first_bad = 0;  // scans are paired after the loop, so bad messages come out of order
  const auto mark_bad = [&](uint64_t message, const std::string& why) {
    if (first_bad == 0 || message < first_bad) {
      first_bad = message;
      stats.first_bad = fmt::format("message {}: {}", message, why);
    }
    ++stats.bad_lines;
  };
  OdometryTrack track(options.max_odometry_gap_s);
  StaticFrames frames;
  std::string base_frame;
  std::vector<PendingScan> pending;
  for (const mcap::MessageView& m : contents.messages) {
    const uint64_t number = static_cast<uint64_t>(++stats.lines);
    const mcap::Channel& channel = contents.channels.at(m.channel_id);
    if (m.channel_id == *scan_channel) {
      auto scan = decode_laser_scan(m.data);
      if (!scan) {
        mark_bad(number, channel.topic + ": " + scan.message());
        continue;
      }
      pending.push_back({number, std::move(*scan)});
    } else if (m.channel_id == *odom_channel) {
      auto odom = decode_odometry(m.data);
      if (!odom) {
        mark_bad(number, channel.topic + ": " + odom.message());
        continue;
      }
      ++stats.odometry;
      if (base_frame.empty()) base_frame = odom->child_frame_id;
      track.add(odom->header.stamp_s, {odom->position.x, odom->position.y, yaw_of(odom->orientation)});
    } else if (channel.topic == "/tf_static" && has_type(contents, channel, kTfMessageType)) {
      auto transforms = decode_tf_message(m.data);
      if (!transforms) {
        mark_bad(number, channel.topic + ": " + transforms.message());
        continue;
      }
      for (const Ros2Transform& t : *transforms) frames.add(t);
    } else {
      ++stats.unknown_kinds;
    }
  }

  std::optional<LaserMount> mount;
  std::string mount_frame;
  for (PendingScan& p : pending) {
    const auto odom = track.at(p.scan.header.stamp_s);
    if (!odom) {
      mark_bad(p.message, fmt::format("scan at {:.3f} s has no odometry within {} s", p.scan.header.stamp_s,
                                      options.max_odometry_gap_s));
      continue;
    }
    if (mount_frame != p.scan.header.frame_id || !mount) {
      mount_frame = p.scan.header.frame_id;
      mount = frames.mount(base_frame, mount_frame);
    }
    LaserScan scan = to_laser_scan(std::move(p.scan), *odom, mount);
    count_scan(scan, log.scans.empty() ? nullptr : &log.scans.back(), stats);
    log.scans.push_back(std::move(scan));
  }
  return log;
}

Result<RobotLog> read_ros2_mcap_log(const std::filesystem::path& path, const Ros2McapOptions& options) {
  auto file = mcap::MappedFile::open(path.string());
  if (!file) return file.error();
  auto contents = mcap::parse((*file)->bytes());
  if (!contents) return Error{path.string() + ": " + contents.message()};
  auto log = ros2_log_from_mcap(*contents, options);
  if (!log) return Error{path.string() + ": " + log.message()};
  return log;
}

}  // namespace slam::robot_log
