#pragma once
// Every robot the viewer has heard of: what it reported (state, path, points) and how the
// operator wants it shown (colour, size, point radius, last N points, its own goal mode).
// Robots are never removed, so indices are stable and the GPU layer keeps one buffer per index.
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/core/latest_stamps.hpp"
#include "viewer/core/cell_colors.hpp"
#include "viewer/core/intake_types.hpp"
#include "viewer/core/point_store.hpp"

namespace slam::viewer {

struct RobotSettings {
  Rgba color{1.0f, 1.0f, 1.0f, 1.0f};  // replaced by default_robot_color() for new robots
  float size_m = 0.35f;                // drawn triangle length
  float point_radius_px = 2.0f;
  uint32_t last_n = 0;  // 0: every point
  bool visible = true;
  bool show_path = true;
  GoalMode mode = GoalMode::Direct;
};

struct RobotView {
  explicit RobotView(std::string robot_id, size_t max_points) : id(std::move(robot_id)), points(max_points) {}
  std::string id;
  RobotSettings settings;
  bool has_state = false;
  msg::RobotState state;
  bool has_path = false;
  msg::RobotPath path;
  bool has_mission = false;
  msg::Mission mission;
  bool has_correction = false;
  msg::PoseCorrection correction;
  // Map frame: each point went through the robot's correction of the moment it arrived. A later
  // correction fixes the robot's drift from then on; it does not move what was already placed
  // (re-applying the newest correction to old points rotates them by every heading fix since).
  PointStore points;
  uint64_t observations = 0;
  Pose last_observed_pose;

  // The robot's current correction map <- odom; the identity before the mapper sent one.
  Pose map_from_odom() const { return has_correction ? correction.map_from_odom : Pose{}; }
};

class RobotRegistry {
 public:
  explicit RobotRegistry(size_t max_points_per_robot = size_t{16} << 20)
      : max_points_(max_points_per_robot) {}

  RobotView& get_or_add(const std::string& id);
  RobotView* find(const std::string& id);
  size_t size() const { return robots_.size(); }
  RobotView& at(size_t index) { return *robots_[index]; }
  const RobotView& at(size_t index) const { return *robots_[index]; }

  void ingest(const ObservationData& o);
  // A robot's pose comes from its state record and from the digests: the report of its latest
  // message wins (LatestStamps), and a forgotten robot stays forgotten until it speaks again.
  void ingest(msg::RobotState&& s);
  void ingest(const msg::RobotPose& p);
  void ingest(msg::RobotPath&& p);
  void ingest(msg::Mission&& m);
  // A robot's first correction, or one an operator set, also moves the points placed before it:
  // they were placed in a frame now known to be wrong.
  void ingest(msg::PoseCorrection&& c);
  // The operator forgot the robot: its view, settings and points go, and the robots after it move
  // up one place. False when it was not known.
  bool forget(const std::string& id);
  // Bumped by every forget: whoever keeps data by robot position (the GL point buffers) rebuilds it.
  uint64_t removals() const { return removals_; }

  // Settings given to robots seen from now on; apply_defaults_to_all() pushes them to every robot.
  RobotSettings& defaults() { return defaults_; }
  void apply_defaults_to_all();

  size_t online() const;
  size_t total_points() const;
  // Box around every robot position and point; false when there is nothing.
  bool bounds(WorldBox* box) const;

 private:
  std::vector<float> placed_xy_;  // reused: one observation's points in the map frame
  LatestStamps pose_stamps_;      // which report of each robot's pose is the newest
  size_t max_points_;
  RobotSettings defaults_;
  std::vector<std::unique_ptr<RobotView>> robots_;
  std::unordered_map<std::string, size_t> index_;  // id -> position in robots_
  uint64_t removals_ = 0;
};

}  // namespace slam::viewer
