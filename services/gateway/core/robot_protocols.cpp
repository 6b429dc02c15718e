#include "gateway/core/robot_protocols.hpp"

namespace slam::gateway {

std::optional<LearntProtocol> fresher(const std::optional<LearntProtocol>& a,
                                      const std::optional<LearntProtocol>& b) {
  if (!a) return b;
  if (!b) return a;
  return b->last_seen_ns > a->last_seen_ns ? b : a;
}

bool RobotProtocols::learn(std::string_view id, LearntProtocol report) {
  if (const auto it = robots_.find(id); it != robots_.end()) {
    if (report.last_seen_ns > it->second.last_seen_ns) it->second = report;
    return true;
  }
  if (robots_.size() >= max_robots_) return false;
  robots_.emplace(std::string(id), report);
  return true;
}

std::optional<LearntProtocol> RobotProtocols::find(std::string_view id) const {
  const auto it = robots_.find(id);
  if (it == robots_.end()) return std::nullopt;
  return it->second;
}

void RobotProtocols::for_each_id(const std::function<void(const std::string&)>& fn) const {
  for (const auto& [id, report] : robots_) fn(id);
}

}  // namespace slam::gateway
