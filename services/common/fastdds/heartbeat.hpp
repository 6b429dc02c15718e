#pragma once
// Publishes the service's Heartbeat (name, instance, pid, host, uptime, counters) once a period
// from its own thread, so a busy service loop still reports; its counters show whether it makes progress.
#include <chrono>
#include <memory>
#include <string>

#include "common/core/counters.hpp"
#include "common/core/service_identity.hpp"
#include "common/fastdds/fast_topics.hpp"

namespace slam {

class HeartbeatPublisher {
 public:
  static Result<std::unique_ptr<HeartbeatPublisher>> start(
      dds::Participant& participant, std::string service, const Counters& counters,
      std::chrono::milliseconds period = std::chrono::seconds(1));

  // Marks the service running (after activation) or stopping (during shutdown); sent at once.
  void set_state(ServiceState state) { loop_->set_state(state); }
  const std::string& instance_id() const { return loop_->identity().instance_id; }

 private:
  HeartbeatPublisher() = default;
  void write(const HeartbeatContent& content);

  std::unique_ptr<dds::Writer<Heartbeat>> writer_;
  Heartbeat sample_;                     // reused: the loop never writes twice at once
  std::unique_ptr<HeartbeatLoop> loop_;  // last: stops first
};

}  // namespace slam
