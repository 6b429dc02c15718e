// A robot's trajectory from the store, and its TUM / CARMEN text (see trajectory_export.hpp).
#include "mapper/core/trajectory_export.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <system_error>
#include <unordered_map>

namespace slam::mapper {
namespace {

constexpr std::string_view kCarmenHost = "slamfleet";

// Nanoseconds as seconds with nine decimals, exactly: a double would lose the last digits of an epoch.
std::string seconds_text(int64_t ns) {
  const int64_t whole = ns / 1'000'000'000;
  const int64_t fraction = std::abs(ns % 1'000'000'000);
  return fmt::format("{}{}.{:09d}", ns < 0 && whole == 0 ? "-" : "", whole, fraction);
}

void append_line(std::string& out, const TrajectoryPose& p, TrajectoryFormat format) {
  const std::string stamp = seconds_text(p.stamp_ns);
  if (format == TrajectoryFormat::Tum) {
    const double half = 0.5 * p.pose.theta;
    out += fmt::format("{} {:.6f} {:.6f} 0 0 0 {:.9f} {:.9f}\n", stamp, p.pose.x, p.pose.y, std::sin(half),
                       std::cos(half));
  } else {
    out += fmt::format("ODOM {:.6f} {:.6f} {:.6f} 0 0 0 {} {} {}\n", p.pose.x, p.pose.y, p.pose.theta, stamp,
                       kCarmenHost, stamp);
  }
}

}  // namespace

std::optional<TrajectoryFormat> trajectory_format_named(std::string_view name) {
  if (name == "tum") return TrajectoryFormat::Tum;
  if (name == "carmen") return TrajectoryFormat::Carmen;
  return std::nullopt;
}

Result<std::vector<TrajectoryPose>> robot_trajectory(ObservationStore& store, std::string_view robot) {
  auto keyframes = store.keyframes();
  if (!keyframes) return keyframes.error();
  std::unordered_map<KeyframeId, Pose> corrections;
  for (const Keyframe& k : *keyframes)
    if (k.robot_id == robot) corrections.emplace(k.id, k.map_from_odom);

  std::vector<TrajectoryPose> out;
  Pose latest;  // the correction of the robot's nearest keyframe so far: identity before any
  SLAM_TRY(store.for_each_pose(robot, [&](const ObservationRecord& r) {
    if (const auto it = corrections.find(r.keyframe_id); it != corrections.end()) latest = it->second;
    const Pose odom{r.obs.x, r.obs.y, r.obs.has_heading ? r.obs.theta : 0.0};
    Pose map = latest.compose(odom);
    if (!r.obs.has_heading) map.theta = 0.0;  // no heading to turn (as the grid's view keeps it)
    out.push_back({r.robot_stamp_ns != 0 ? r.robot_stamp_ns : r.stamp_ns, map, r.obs.has_heading});
  }));
  return out;
}

Status write_trajectory(std::span<const TrajectoryPose> poses, const std::filesystem::path& path,
                        TrajectoryFormat format) {
  std::string text;
  text.reserve(poses.size() * 80);
  for (const TrajectoryPose& p : poses) append_line(text, p, format);
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) return Error{path.string() + ": cannot open for writing"};
  file.write(text.data(), static_cast<std::streamsize>(text.size()));
  file.flush();
  if (!file) return Error{path.string() + ": write error"};
  return Status::ok();
}

FileOutcome export_trajectory_file(ObservationStore& store, std::string_view robot, const std::string& path,
                                   TrajectoryFormat format) {
  if (robot.empty()) return FileOutcome::failed(MapError::InvalidRequest, "robot_id is empty");
  if (path.empty())
    return FileOutcome::failed(MapError::InvalidRequest, "the trajectory file's path is empty");
  if (path.find('\0') != std::string::npos)
    return FileOutcome::failed(MapError::InvalidRequest,
                               "the trajectory file's path contains a NUL character");
  const std::filesystem::path p(path);
  const std::filesystem::path dir = p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    return FileOutcome::failed(MapError::Io, "directory " + dir.string() + " does not exist");
  auto poses = robot_trajectory(store, robot);
  if (!poses) return FileOutcome::failed(MapError::Io, poses.message());
  if (poses->empty())
    return FileOutcome::failed(MapError::UnknownRobot,
                               "no stored observations of robot '" + std::string(robot) + "'");
  if (Status s = write_trajectory(*poses, p, format); !s)
    return FileOutcome::failed(MapError::Io, s.message());
  return FileOutcome{
      {},
      fmt::format("wrote {} poses of robot '{}' ({} to {} s) to {}", poses->size(), robot,
                  seconds_text(poses->front().stamp_ns), seconds_text(poses->back().stamp_ns), path),
      {}};
}

}  // namespace slam::mapper
