#pragma once
// What a heartbeat says about its process, whichever DDS vendor publishes it (Fast DDS services,
// the Cyclone simulator), and the thread that publishes it once a period.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "common/core/counters.hpp"

namespace slam {

struct ServiceIdentity {
  std::string service;
  std::string host;
  std::string instance_id;  // "host:pid": unique per running process
  uint32_t pid = 0;
  std::chrono::steady_clock::time_point started;

  static ServiceIdentity of(std::string service);
  double uptime_s() const;
};

// Calls `tick` every `period` from its own thread until destroyed (not at construction).
class PeriodicTask {
 public:
  PeriodicTask(std::chrono::milliseconds period, std::function<void()> tick);
  ~PeriodicTask();
  PeriodicTask(const PeriodicTask&) = delete;
  PeriodicTask& operator=(const PeriodicTask&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// One heartbeat's content, before a DDS vendor turns it into its Heartbeat sample.
struct HeartbeatContent {
  const ServiceIdentity& identity;
  int64_t stamp_ns;
  double uptime_s;
  uint32_t state;  // the IDL ServiceState value
  const std::vector<std::pair<std::string, int64_t>>& counters;
};

// The vendor-independent half of a heartbeat publisher: identity, state, counters and the thread.
// `write` runs at construction (state STARTING), every `period`, and on each state change, never
// twice at once, so the vendor side may reuse one sample buffer.
class HeartbeatLoop {
 public:
  using Write = std::function<void(const HeartbeatContent&)>;
  HeartbeatLoop(std::string service, const Counters& counters, std::chrono::milliseconds period, Write write);
  HeartbeatLoop(const HeartbeatLoop&) = delete;
  HeartbeatLoop& operator=(const HeartbeatLoop&) = delete;

  void set_state(uint32_t state);
  const ServiceIdentity& identity() const { return identity_; }

 private:
  void publish();

  ServiceIdentity identity_;
  const Counters& counters_;
  Write write_;
  std::atomic<uint32_t> state_{0};  // SERVICE_STARTING in both vendors' generated enums
  std::mutex publish_mutex_;
  std::unique_ptr<PeriodicTask> ticker_;  // last: stops first
};

}  // namespace slam
