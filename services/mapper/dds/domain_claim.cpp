#include "mapper/dds/domain_claim.hpp"

#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "common/core/shutdown.hpp"
#include "mapper/core/sole_mapper.hpp"

namespace slam::mapper {

Result<std::unique_ptr<DomainClaim>> DomainClaim::take(int domain, std::chrono::milliseconds listen) {
  std::unique_ptr<DomainClaim> claim(new DomainClaim());
  auto participant = dds::Participant::create(domain, "slam-mapper-claim");
  if (!participant) return participant.error();
  claim->participant_ = std::move(*participant);

  std::mutex mutex;
  std::map<std::string, MapperPeer> peers;  // by instance id: the latest heartbeat of each mapper
  auto reader = dds::make_reader(*claim->participant_, dds::kHeartbeat, [&](const Heartbeat& h, const auto&) {
    if (h.service() != "mapper") return;
    std::lock_guard lock(mutex);
    const std::string id = h.instance_id().to_string();
    if (h.state() == SERVICE_STOPPING) {
      peers.erase(id);
      return;
    }
    peers[id] = MapperPeer{id, h.host().to_string(), h.pid(), h.state() == SERVICE_RUNNING};
  });
  if (!reader) return reader.error();
  auto heartbeat = HeartbeatPublisher::start(*claim->participant_, "mapper", claim->counters_);
  if (!heartbeat) return heartbeat.error();
  claim->heartbeat_ = std::move(*heartbeat);

  const auto until = std::chrono::steady_clock::now() + listen;
  while (std::chrono::steady_clock::now() < until && !shutdown_requested())
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  (*reader).reset();

  std::vector<MapperPeer> seen;
  for (const auto& [id, peer] : peers) seen.push_back(peer);
  if (auto peer = yield_to(claim->heartbeat_->instance_id(), seen)) return Error{refusal(*peer, domain)};
  claim->heartbeat_->set_state(SERVICE_RUNNING);
  return claim;
}

}  // namespace slam::mapper
