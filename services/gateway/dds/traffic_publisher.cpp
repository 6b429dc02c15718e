// TrafficPublisher: drain in batches, write each record, stop when asked.
#include "gateway/dds/traffic_publisher.hpp"

#include <chrono>

#include "common/core/guarded_callback.hpp"
#include "gateway/dds/gateway_msgs.hpp"

namespace slam::gateway {

Result<std::unique_ptr<TrafficPublisher>> TrafficPublisher::start(dds::Participant& participant,
                                                                  TrafficQueue& queue,
                                                                  std::atomic<int64_t>& write_failures) {
  std::unique_ptr<TrafficPublisher> p(new TrafficPublisher(queue, write_failures));
  auto writer = dds::make_writer(participant, dds::kMqttTraffic);
  if (!writer) return writer.error();
  p->writer_ = std::move(*writer);
  p->thread_ = std::thread([raw = p.get()] { raw->run(); });
  return p;
}

TrafficPublisher::~TrafficPublisher() {
  stop_.store(true);
  queue_.close();
  if (thread_.joinable()) thread_.join();
}

void TrafficPublisher::run() {
  std::vector<TrafficRecord> batch = queue_.make_batch(64);
  slam::MqttTraffic sample;
  while (!stop_.load()) {
    guarded_callback("MQTT traffic worker", [&] {
      // The viewer's log need not be fresher than this; records come in batches of up to 64.
      const size_t n = queue_.pop(batch, std::chrono::milliseconds(50));
      for (size_t i = 0; i < n; ++i) {
        fill_traffic(batch[i], sample);
        if (!writer_->write(sample)) bump(write_failures_);
      }
    });
  }
}

}  // namespace slam::gateway
