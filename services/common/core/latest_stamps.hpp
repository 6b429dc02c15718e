#pragma once
// The latest report stamp of each robot, for readers that hear a robot from several sources (its
// RobotState record, the FleetDigest of every gateway that hears it) and must keep the newest. The
// stamp is the gateway's receive time of the robot's latest message (`last_seen_ns`): a report
// older than one already taken is stale, an equal one is the same message (placed again through a
// newer correction) and is taken. After the robot is forgotten, only a strictly newer report brings
// it back: a digest written before its gateway processed the forget carries the old stamp.
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>

namespace slam {

class LatestStamps {
 public:
  enum class Verdict : std::uint8_t {
    Fresh,      // taken: the newest report of this robot so far
    Stale,      // older than a report already taken
    Forgotten,  // the robot was forgotten and this report is not newer than its last one
  };

  // Judges a report of `robot_id` stamped `stamp_ns`; a Fresh one becomes the robot's latest.
  Verdict judge(std::string_view robot_id, std::int64_t stamp_ns);
  // The operator forgot the robot (see the class comment).
  void forget(std::string_view robot_id);

 private:
  struct Hash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  struct Entry {
    std::int64_t stamp_ns = std::numeric_limits<std::int64_t>::min();
    bool forgotten = false;
  };
  std::unordered_map<std::string, Entry, Hash, std::equal_to<>> entries_;
};

}  // namespace slam
