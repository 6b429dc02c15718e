#pragma once
// The DDS side of sole_mapper.hpp: announces this mapper with a heartbeat (STARTING), listens to
// other mappers' heartbeats for a window longer than their period, and either refuses (the line
// names the other mapper) or holds the domain (heartbeat RUNNING) until the service's own heartbeat
// takes over under the same instance id.
#include <chrono>
#include <memory>

#include "common/core/counters.hpp"
#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "common/fastdds/heartbeat.hpp"

namespace slam::mapper {

class DomainClaim {
 public:
  static constexpr std::chrono::milliseconds kListen{2500};  // > the heartbeat period (1 s) + discovery

  // An error (the refusal line) when another mapper holds or is taking the domain.
  static Result<std::unique_ptr<DomainClaim>> take(int domain, std::chrono::milliseconds listen = kListen);

 private:
  DomainClaim() = default;

  Counters counters_;  // none: the heartbeat only says who this is
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<HeartbeatPublisher> heartbeat_;
};

}  // namespace slam::mapper
