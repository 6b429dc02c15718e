#pragma once
// What the bridge knows about the fleet, built from the DDS topics it reads and read by every face
// it serves (the Foxglove WebSocket face and the ROS 2 face). Plain C++: the DDS edge converts
// samples into the fleet's plain messages (common/core/fleet_messages.hpp) and ObservationInput.
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/core/fleet_messages.hpp"
#include "common/core/geometry.hpp"
#include "common/core/latest_stamps.hpp"

namespace slam::bridge {

// Recent obstacle points of one robot, in the map frame (the gateways place them).
struct ObservationInput {
  std::string robot_id;
  std::vector<Vec2> hits;
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
  msg::RobotPose state;  // from the gateways' FleetDigest
  bool has_state = false;
  msg::RobotPath path;
  bool has_path = false;
  PointRing points;  // map frame
};

struct ServiceView {
  msg::Heartbeat beat;
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
  void ingest(const msg::RobotPose& s);
  void ingest(msg::RobotPath&& p);
  void ingest(const ObservationInput& o);
  void ingest(msg::Heartbeat&& h, int64_t now_mono_ns);
  // An operator alert's latest state, active or cleared.
  void ingest(msg::Alert&& a);
  // The operator forgot the robot: it leaves the model; its paths and points are ignored until a
  // newer message of it arrives.
  void forget(const std::string& robot_id);

  // By robot id (sorted, so every message lists robots in the same order).
  const std::map<std::string, RobotView>& robots() const { return robots_; }
  // By (service, instance id).
  const std::map<std::pair<std::string, std::string>, ServiceView>& services() const { return services_; }
  // By alert id.
  const std::map<std::string, msg::Alert>& alerts() const { return alerts_; }
  const FleetVersions& versions() const { return versions_; }

 private:
  RobotView& robot(const std::string& id);

  size_t points_per_robot_;
  LatestStamps state_stamps_;
  std::set<std::string> forgotten_;  // until a newer state brings the robot back
  std::map<std::string, RobotView> robots_;
  std::map<std::pair<std::string, std::string>, ServiceView> services_;
  std::map<std::string, msg::Alert> alerts_;
  FleetVersions versions_;
};

}  // namespace slam::bridge
