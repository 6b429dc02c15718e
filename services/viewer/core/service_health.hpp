#pragma once
// Every service's latest heartbeat and when it arrived, so the Main tab can say which services
// are alive (a heartbeat within the last 3 s and not stopping), with their counters.
#include <cstdint>
#include <vector>

#include "viewer/core/intake_types.hpp"

namespace slam::viewer {

struct ServiceEntry {
  msg::Heartbeat heartbeat;
  int64_t last_seen_ns = 0;  // monotonic
  uint64_t beats = 0;
};

class ServiceHealth {
 public:
  static constexpr int64_t kAliveWindowNs = 3'000'000'000;

  void update(msg::Heartbeat&& hb, int64_t now_ns);
  // Sorted by service name, then instance.
  const std::vector<ServiceEntry>& entries() const { return entries_; }
  static bool alive(const ServiceEntry& e, int64_t now_ns) {
    return now_ns - e.last_seen_ns < kAliveWindowNs && e.heartbeat.state != ServiceState::Stopping;
  }

 private:
  std::vector<ServiceEntry> entries_;
};

}  // namespace slam::viewer
