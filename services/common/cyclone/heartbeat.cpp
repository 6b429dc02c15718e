// Turns the vendor-independent heartbeat (common/core/service_identity.hpp) into Cyclone's sample;
// identity fields match the Fast DDS publisher's so the viewer treats every service alike.
#include "common/cyclone/heartbeat.hpp"

#include <spdlog/spdlog.h>

#include "common/core/topics.hpp"
#include "common/cyclone/dds.hpp"

namespace slam::cyclone {

Result<std::unique_ptr<HeartbeatPublisher>> HeartbeatPublisher::start(dds_entity_t participant,
                                                                      std::string service,
                                                                      const Counters& counters,
                                                                      std::chrono::milliseconds period) {
  auto writer = make_writer(participant, &slam_Heartbeat_desc, topics::kHeartbeat);
  if (!writer) return writer.error();
  std::unique_ptr<HeartbeatPublisher> hb(new HeartbeatPublisher());
  hb->writer_ = *writer;
  hb->loop_ = std::make_unique<HeartbeatLoop>(std::move(service), counters, period,
                                              [p = hb.get()](const HeartbeatContent& c) { p->write(c); });
  return hb;
}

void HeartbeatPublisher::write(const HeartbeatContent& content) {
  counter_samples_.resize(content.counters.size());
  for (size_t i = 0; i < content.counters.size(); ++i) {
    copy_bounded(content.counters[i].first, counter_samples_[i].name, sizeof counter_samples_[i].name);
    counter_samples_[i].value = content.counters[i].second;
  }
  slam_Heartbeat sample{};
  copy_bounded(content.identity.service, sample.service, sizeof sample.service);
  copy_bounded(content.identity.instance_id, sample.instance_id, sizeof sample.instance_id);
  sample.pid = content.identity.pid;
  copy_bounded(content.identity.host, sample.host, sizeof sample.host);
  sample.stamp_ns = content.stamp_ns;
  sample.uptime_s = content.uptime_s;
  sample.state = static_cast<slam_ServiceState>(content.state);
  sample.counters = {static_cast<uint32_t>(counter_samples_.size()),
                     static_cast<uint32_t>(counter_samples_.size()), counter_samples_.data(), false};
  const dds_return_t rc = dds_write(writer_, &sample);
  if (rc != DDS_RETCODE_OK) spdlog::warn("writing {}: {}", topics::kHeartbeat.name, dds_strretcode(rc));
}

}  // namespace slam::cyclone
