// Latest heartbeat per service instance (see service_health.hpp).
#include "viewer/core/service_health.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

namespace slam::viewer {

void ServiceHealth::update(msg::Heartbeat&& hb, int64_t now_ns) {
  for (auto& e : entries_)
    if (e.heartbeat.service == hb.service && e.heartbeat.instance_id == hb.instance_id) {
      e.heartbeat = std::move(hb);
      e.last_seen_ns = now_ns;
      ++e.beats;
      return;
    }
  entries_.push_back({std::move(hb), now_ns, 1});
  std::sort(entries_.begin(), entries_.end(), [](const ServiceEntry& a, const ServiceEntry& b) {
    return std::tie(a.heartbeat.service, a.heartbeat.instance_id) <
           std::tie(b.heartbeat.service, b.heartbeat.instance_id);
  });
}

}  // namespace slam::viewer
