// Heartbeat sample assembly and the publishing thread; identity fields match the Fast DDS
// publisher's (instance id "host:pid") so the viewer treats every service alike.
#include "common/cyclone/heartbeat.hpp"

#include <spdlog/spdlog.h>

#include "common/core/clock.hpp"
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
  hb->counters_ = &counters;
  hb->identity_ = ServiceIdentity::of(std::move(service));
  hb->publish();
  hb->ticker_ = std::make_unique<PeriodicTask>(period, [p = hb.get()] { p->publish(); });
  return hb;
}

HeartbeatPublisher::~HeartbeatPublisher() {
  ticker_.reset();
}

void HeartbeatPublisher::set_state(slam_ServiceState state) {
  state_ = state;
  publish();
}

void HeartbeatPublisher::publish() {
  std::lock_guard lock(publish_mutex_);
  const auto counters = counters_->snapshot();
  counter_samples_.resize(counters.size());
  for (size_t i = 0; i < counters.size(); ++i) {
    cyclone::copy_bounded(counters[i].first, counter_samples_[i].name, sizeof counter_samples_[i].name);
    counter_samples_[i].value = counters[i].second;
  }
  slam_Heartbeat sample{};
  cyclone::copy_bounded(identity_.service, sample.service, sizeof sample.service);
  cyclone::copy_bounded(identity_.instance_id, sample.instance_id, sizeof sample.instance_id);
  sample.pid = identity_.pid;
  cyclone::copy_bounded(identity_.host, sample.host, sizeof sample.host);
  sample.stamp_ns = now_ns();
  sample.uptime_s = identity_.uptime_s();
  sample.state = state_.load();
  sample.counters = {static_cast<uint32_t>(counter_samples_.size()),
                     static_cast<uint32_t>(counter_samples_.size()), counter_samples_.data(), false};
  const dds_return_t rc = dds_write(writer_, &sample);
  if (rc != DDS_RETCODE_OK) spdlog::warn("writing {}: {}", topics::kHeartbeat.name, dds_strretcode(rc));
}

}  // namespace slam::cyclone
