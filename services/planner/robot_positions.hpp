#pragma once
// The newest position of each robot, from several sources: its RobotState (a status record, once
// a second or on a presence change) and the FleetDigest of every gateway that hears it (every
// robot, ten times a second). Each source stamps a position with the gateway's receive time of the
// robot's latest message; a position older than one already taken is stale (a slow state record,
// or the digest of a gateway that no longer hears the robot) and is dropped. Equal stamps are
// taken: the same message placed again through a newer correction.
// Plain C++, single-threaded (the planner's intake calls it under its lock); buffers are reused.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::planner {

struct RobotPosition {
  std::string robot_id;
  Vec2 position;
  int64_t last_seen_ns = 0;
};

class RobotPositions {
 public:
  // Keeps `position` unless a position heard later (larger last_seen_ns) was offered before.
  // Returns whether it was kept.
  bool offer(std::string_view robot_id, Vec2 position, int64_t last_seen_ns);
  // Moves the newest position of each robot offered since the last take into `out` (replaced).
  void take(std::vector<RobotPosition>& out);
  // The robot was forgotten: whatever it reports next is taken, whatever its stamp.
  void forget(std::string_view robot_id);

 private:
  struct Hash {
    using is_transparent = void;
    size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  struct Seen {
    int64_t last_seen_ns = std::numeric_limits<int64_t>::min();
    uint64_t round = 0;  // the take() round its entry in pending_ belongs to
    size_t index = 0;    // in pending_, valid in that round only
  };
  std::unordered_map<std::string, Seen, Hash, std::equal_to<>> seen_;
  std::vector<RobotPosition> pending_;
  uint64_t round_ = 1;
};

}  // namespace slam::planner
