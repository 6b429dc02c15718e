#pragma once
// The worker that turns queued MQTT traffic records into MqttTraffic samples, off the MQTT
// thread, so a slow or busy DDS side never delays message handling.
#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "common/core/counters.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "gateway/core/traffic_queue.hpp"

namespace slam::gateway {

class TrafficPublisher {
 public:
  static Result<std::unique_ptr<TrafficPublisher>> start(dds::Participant& participant, TrafficQueue& queue,
                                                         std::atomic<int64_t>& write_failures);
  // Closes the queue and joins the worker.
  ~TrafficPublisher();
  TrafficPublisher(const TrafficPublisher&) = delete;
  TrafficPublisher& operator=(const TrafficPublisher&) = delete;

 private:
  TrafficPublisher(TrafficQueue& queue, std::atomic<int64_t>& write_failures)
      : queue_(queue), write_failures_(write_failures) {}
  void run();

  TrafficQueue& queue_;
  std::atomic<int64_t>& write_failures_;
  std::unique_ptr<dds::Writer<slam::MqttTraffic>> writer_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace slam::gateway
