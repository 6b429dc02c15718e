#pragma once
// What a heartbeat says about its process, whichever DDS vendor publishes it (Fast DDS services,
// the Cyclone simulator), and the thread that publishes it once a period.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

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

}  // namespace slam
