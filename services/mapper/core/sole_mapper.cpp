#include "mapper/core/sole_mapper.hpp"

namespace slam::mapper {

std::optional<MapperPeer> yield_to(const std::string& self, const std::vector<MapperPeer>& peers) {
  std::optional<MapperPeer> lowest;
  for (const MapperPeer& p : peers) {
    if (p.instance_id == self) continue;
    if (p.holds_domain) return p;
    if (p.instance_id < self && (!lowest || p.instance_id < lowest->instance_id)) lowest = p;
  }
  return lowest;
}

std::string refusal(const MapperPeer& peer, int domain) {
  return "another mapper " + std::string(peer.holds_domain ? "runs" : "is starting") + " on DDS domain " +
         std::to_string(domain) + " (host " + peer.host + ", pid " + std::to_string(peer.pid) +
         "): one mapper owns the map (its store is on its own disk); stop that one or use another domain";
}

}  // namespace slam::mapper
