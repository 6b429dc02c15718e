#pragma once
// Other robots are not walls. A robot's sensor sees the robots around it, and a hit on one would
// stay in the map as an obstacle after it drove on: passing robots leave blobs that close 1.2 m
// corridors and make the planner re-plan. A hit within `radius_m` of where another robot was
// reported recently is turned into a miss (the beam was free up to it), before the observation is
// stored, so live integration and rebuilds from the store agree.
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "common/core/result.hpp"
#include "mapper/core/occupancy_grid.hpp"

namespace slam::mapper {

struct FootprintConfig {
  double radius_m = 0.35;  // a robot's radius plus its pose error; 0 turns the filter off
  double max_age_s = 2.0;  // a pose older than this no longer marks where the robot is
};

Status validate(const FootprintConfig& config);

class RobotFootprints {
 public:
  explicit RobotFootprints(const FootprintConfig& config);

  // Moves the hits that lie near another robot's recent position to `misses`, then records
  // `position` as robot_id's at now_ns. Returns how many hits were moved. Allocation-free once
  // every robot has been seen (a fleet of hundreds is a flat scan per observation).
  // `odom_hits`/`odom_misses`, when given, hold the same points in the robot's odometry frame (the
  // ones stored) and get the same moves.
  size_t apply(std::string_view robot_id, Vec2 position, int64_t now_ns, std::vector<Vec2>& hits,
               std::vector<Vec2>& misses, std::vector<Vec2>* odom_hits = nullptr,
               std::vector<Vec2>* odom_misses = nullptr);

  size_t robots() const { return sightings_.size(); }

 private:
  // Where a robot was last reported, and when.
  struct Sighting {
    Vec2 position;
    int64_t seen_ns = 0;
  };
  // Lets the map be searched with a string_view (no string built per observation).
  struct IdHash {
    using is_transparent = void;
    size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };

  double radius2_;
  int64_t max_age_ns_;
  std::unordered_map<std::string, size_t, IdHash, std::equal_to<>> slots_;  // robot id -> sightings_ index
  std::vector<Sighting> sightings_;
  std::vector<Vec2> near_;  // scratch: other robots within reach of this observation
};

}  // namespace slam::mapper
