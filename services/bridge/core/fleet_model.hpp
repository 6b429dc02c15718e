#pragma once
// What the bridge knows about the fleet, built from the DDS topics it reads and read by every face
// it serves (the Foxglove WebSocket face today; a ROS 2 DDS face would read the same model).
// Plain C++: the DDS edge converts samples into the *Input types below.
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/latest_stamps.hpp"

namespace slam::bridge {

struct RobotStateInput {
  std::string robot_id;
  Pose pose;  // map frame
  bool has_heading = false;
  bool online = true;
  int64_t stamp_ns = 0;  // the robot's last message: the newest wins when several gateways list it
};

enum class PathStatus { None, Active, Reached, Failed };

struct RobotPathInput {
  std::string robot_id;
  PathStatus status = PathStatus::None;
  std::string mode;  // "planned", "explore", ...
  Vec2 target;
  std::vector<Vec2> waypoints;  // map frame
  uint32_t current = 0;         // index of the waypoint being driven to
};

// Recent obstacle points of one robot, in the map frame (the gateways place them).
struct ObservationInput {
  std::string robot_id;
  std::vector<Vec2> hits;
};

struct HeartbeatInput {
  std::string service;
  std::string instance_id;
  std::string host;
  uint32_t pid = 0;
  std::string state;  // "starting", "running", "stopping"
  double uptime_s = 0.0;
};

// An operator alert (system.idl Alert): its latest state, active or cleared.
struct AlertInput {
  std::string alert_id;
  std::string kind;  // "robot_offline", "service_silent", "battery_low"
  std::string subject;
  bool active = false;
  int64_t raised_ns = 0;  // Unix epoch
  int64_t stamp_ns = 0;
  std::string message;
  std::string raised_by;
};

// The last `capacity` points of one robot, oldest overwritten first.
class PointRing {
 public:
  explicit PointRing(size_t capacity = 0) : capacity_(capacity) {}
  void add(Vec2 p);
  size_t size() const { return points_.size(); }
  // Calls f(point) for every point, in no particular order.
  template <class F>
  void for_each(F&& f) const {
    for (const Vec2& p : points_) f(p);
  }

 private:
  size_t capacity_;
  size_t next_ = 0;
  std::vector<Vec2> points_;
};

struct RobotView {
  explicit RobotView(size_t points_per_robot) : points(points_per_robot) {}
  RobotStateInput state;
  bool has_state = false;
  RobotPathInput path;
  bool has_path = false;
  PointRing points;  // map frame
};

struct ServiceView {
  HeartbeatInput beat;
  int64_t heard_ns = 0;  // monotonic
};

// Change counters: a face compares them with what it sent last to know whether a channel has news.
struct FleetVersions {
  uint64_t robots = 0;
  uint64_t paths = 0;
  uint64_t points = 0;
  uint64_t health = 0;
  uint64_t alerts = 0;
};

class FleetModel {
 public:
  explicit FleetModel(size_t points_per_robot) : points_per_robot_(points_per_robot) {}

  // Kept unless the robot's state already is from a later message (another gateway's older view),
  // or the robot was forgotten and this is not a newer message (LatestStamps).
  void ingest(const RobotStateInput& s);
  void ingest(RobotPathInput&& p);
  void ingest(const ObservationInput& o);
  void ingest(const HeartbeatInput& h, int64_t now_mono_ns);
  void ingest(AlertInput&& a);
  // The operator forgot the robot: it leaves the model; its paths and points are ignored until a
  // newer message of it arrives.
  void forget(const std::string& robot_id);

  // By robot id (sorted, so every message lists robots in the same order).
  const std::map<std::string, RobotView>& robots() const { return robots_; }
  // By (service, instance id).
  const std::map<std::pair<std::string, std::string>, ServiceView>& services() const { return services_; }
  // By alert id.
  const std::map<std::string, AlertInput>& alerts() const { return alerts_; }
  const FleetVersions& versions() const { return versions_; }

 private:
  RobotView& robot(const std::string& id);

  size_t points_per_robot_;
  LatestStamps state_stamps_;
  std::set<std::string> forgotten_;  // until a newer state brings the robot back
  std::map<std::string, RobotView> robots_;
  std::map<std::pair<std::string, std::string>, ServiceView> services_;
  std::map<std::string, AlertInput> alerts_;
  FleetVersions versions_;
};

}  // namespace slam::bridge
