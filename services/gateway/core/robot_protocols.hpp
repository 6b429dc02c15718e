#pragma once
// The protocol each robot speaks as every gateway learnt it, from the RobotStates on DDS. With
// shared subscriptions a robot's messages are spread over the gateways, so the one that owns the
// robot (and sends its waypoints) may have received none of them: it answers in the protocol the
// freshest report, its own registry's or a peer's RobotState, says. Plain; the loop owns it.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

#include "gateway/core/robot_registry.hpp"

namespace slam::gateway {

// A protocol and when the message that showed it arrived (wall clock, as RobotState.last_seen_ns).
struct LearntProtocol {
  Protocol protocol = Protocol::V1;
  std::int64_t last_seen_ns = 0;
};

// The fresher of two reports; nullopt when there is neither.
std::optional<LearntProtocol> fresher(const std::optional<LearntProtocol>& a,
                                      const std::optional<LearntProtocol>& b);

class RobotProtocols {
 public:
  explicit RobotProtocols(std::size_t max_robots) : max_robots_(max_robots) {}

  // Keeps the report unless an equally fresh or fresher one is known. False when the robot is new
  // and max_robots are known already (memory stays bounded).
  bool learn(std::string_view id, LearntProtocol report);
  std::optional<LearntProtocol> find(std::string_view id) const;
  // The operator forgot the robot.
  void forget(std::string_view id) {
    if (const auto it = robots_.find(id); it != robots_.end()) robots_.erase(it);
  }
  std::size_t size() const { return robots_.size(); }
  void for_each_id(const std::function<void(const std::string&)>& fn) const;

 private:
  struct Hash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  std::size_t max_robots_;
  std::unordered_map<std::string, LearntProtocol, Hash, std::equal_to<>> robots_;
};

}  // namespace slam::gateway
