#pragma once
// Publishes the service's Heartbeat (name, instance, pid, host, uptime, counters) once a period
// from its own thread, so a busy service loop still reports; its counters show whether it makes progress.
#include <atomic>
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
  ~HeartbeatPublisher();

  // Marks the service running (after activation) or stopping (during shutdown); sent at once.
  void set_state(ServiceState state);
  const std::string& instance_id() const { return identity_.instance_id; }

 private:
  HeartbeatPublisher() = default;
  void publish();

  std::unique_ptr<dds::Writer<Heartbeat>> writer_;
  const Counters* counters_ = nullptr;
  ServiceIdentity identity_;
  std::atomic<ServiceState> state_{SERVICE_STARTING};
  std::mutex publish_mutex_;
  Heartbeat sample_;
  std::unique_ptr<PeriodicTask> ticker_;  // last: stops first
};

}  // namespace slam
