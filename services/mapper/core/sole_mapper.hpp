#pragma once
// One mapper per domain. The map lives in the active mapper's store, on its disk: a second mapper
// would build a second map from the same observations and both would publish snapshots and patches
// under different layouts, splitting the map for every reader. A standby on another host would have
// none of the stored observations, so there is no hot standby: a second mapper refuses to start.
// The rule (plain, below): before opening its store a mapper announces itself (heartbeat STARTING)
// and listens for other mappers' heartbeats; it yields to one that holds the domain (RUNNING), and
// of two that start at the same moment the lower instance id ("host:pid") stays.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace slam::mapper {

struct MapperPeer {
  std::string instance_id;  // "host:pid"
  std::string host;
  uint32_t pid = 0;
  bool holds_domain = false;  // RUNNING: it won its own start-up check
};

// The peer this mapper must yield to, if any: one that holds the domain, else the starting one
// with the lowest instance id below `self` (so exactly one of mappers starting together stays).
std::optional<MapperPeer> yield_to(const std::string& self, const std::vector<MapperPeer>& peers);

// The one line a refused mapper exits with.
std::string refusal(const MapperPeer& peer, int domain);

}  // namespace slam::mapper
