#pragma once
// The Heartbeat every service publishes (see common/fastdds/heartbeat.hpp), on Cyclone DDS for the
// simulator: once a period from its own thread with every counter, so a stalled loop still shows
// as alive-but-not-progressing and a dead process as gone (liveliness).
#include <dds/dds.h>
#include <slam/cyclone/system.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "common/core/counters.hpp"
#include "common/core/result.hpp"
#include "common/core/service_identity.hpp"

namespace slam::cyclone {

class HeartbeatPublisher {
 public:
  // Publishes at once (state STARTING), then every `period` until destroyed.
  static Result<std::unique_ptr<HeartbeatPublisher>> start(
      dds_entity_t participant, std::string service, const Counters& counters,
      std::chrono::milliseconds period = std::chrono::seconds(1));
  HeartbeatPublisher(const HeartbeatPublisher&) = delete;
  HeartbeatPublisher& operator=(const HeartbeatPublisher&) = delete;

  // RUNNING after activation, STOPPING during shutdown; published at once.
  void set_state(slam_ServiceState state) { loop_->set_state(state); }

 private:
  HeartbeatPublisher() = default;
  void write(const HeartbeatContent& content);

  dds_entity_t writer_ = 0;                    // child of the participant
  std::vector<slam_Counter> counter_samples_;  // reused: the loop never writes twice at once
  std::unique_ptr<HeartbeatLoop> loop_;        // last: stops first
};

}  // namespace slam::cyclone
