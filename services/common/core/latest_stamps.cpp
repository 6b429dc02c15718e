// LatestStamps: newest-wins per robot, with a floor after a forget (see latest_stamps.hpp).
#include "common/core/latest_stamps.hpp"

namespace slam {

LatestStamps::Verdict LatestStamps::judge(std::string_view robot_id, std::int64_t stamp_ns) {
  auto it = entries_.find(robot_id);
  if (it == entries_.end()) it = entries_.emplace(std::string(robot_id), Entry{}).first;
  Entry& e = it->second;
  if (e.forgotten) {
    if (stamp_ns <= e.stamp_ns) return Verdict::Forgotten;
    e.forgotten = false;
  } else if (stamp_ns < e.stamp_ns) {
    return Verdict::Stale;
  }
  e.stamp_ns = stamp_ns;
  return Verdict::Fresh;
}

void LatestStamps::forget(std::string_view robot_id) {
  auto it = entries_.find(robot_id);
  if (it == entries_.end()) it = entries_.emplace(std::string(robot_id), Entry{}).first;
  it->second.forgotten = true;
}

}  // namespace slam
