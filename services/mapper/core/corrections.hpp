#pragma once
// Pose correction as the grid sees it. Robots report in their own odometry frame; SLAM keeps per
// keyframe the transform map <- odom (p_map = map_from_odom ∘ p_odom). The store keeps observations
// raw (odometry frame) with their keyframe id, so a new set of corrections re-renders the map.
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/core/geometry.hpp"
#include "mapper/core/occupancy_grid.hpp"

namespace slam::mapper {

// Keyframe ids are assigned by the SLAM core; 0 means "no keyframe".
using KeyframeId = uint64_t;

// One keyframe as stored: where the robot's odometry put it, and its correction.
struct Keyframe {
  KeyframeId id = 0;
  std::string robot_id;
  uint32_t segment = 0;  // trajectory segment (a new one starts after an odometry jump)
  Pose odom;             // the keyframe's pose in the robot's odometry frame
  Pose map_from_odom;    // its correction
  bool operator==(const Keyframe&) const = default;
};

// keyframe id -> map_from_odom; identity for 0 and for unknown ids. A value type: a rebuild takes a
// copy to its worker thread.
class KeyframeCorrections {
 public:
  void set(KeyframeId id, const Pose& map_from_odom);
  const Pose& lookup(KeyframeId id) const;
  bool contains(KeyframeId id) const { return poses_.contains(id); }
  bool empty() const { return poses_.empty(); }
  size_t size() const { return poses_.size(); }

 private:
  std::unordered_map<KeyframeId, Pose> poses_;
};

inline bool is_identity(const Pose& p) {
  return p == Pose{};
}

// The map-frame view of an odometry-frame observation: its pose and every point moved by
// map_from_odom into `hits` and `misses` (buffers the caller reuses: no allocation once they are large
// enough). Without a heading theta stays 0 (as the raw view has it).
ObservationView to_map_frame(const Pose& map_from_odom, const ObservationView& odom, std::vector<Vec2>& hits,
                             std::vector<Vec2>& misses);

}  // namespace slam::mapper
