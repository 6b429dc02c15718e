// Heartbeat sample assembly and the publishing thread; identity fields match the Fast DDS
// publisher's (instance id "host:pid") so the viewer treats every service alike.
#include "simulator/cyclone_heartbeat.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "common/clock.hpp"
#include "common/cyclone_qos.hpp"
#include "common/topics.hpp"
#include "simulator/sim_dds.hpp"

namespace slam::sim {

Result<std::unique_ptr<CycloneHeartbeat>> CycloneHeartbeat::start(dds_entity_t participant, std::string service,
                                                                  const Counters& counters,
                                                                  std::chrono::milliseconds period) {
  const auto qos = cyclone::make_qos(topics::kHeartbeat.qos);
  const dds_entity_t topic = dds_create_topic(participant, &slam_Heartbeat_desc, topics::kHeartbeat.name, qos.get(), nullptr);
  if (topic < 0) return Error{fmt::format("Cyclone topic {}: {}", topics::kHeartbeat.name, dds_strretcode(topic))};
  std::unique_ptr<CycloneHeartbeat> hb(new CycloneHeartbeat());
  hb->writer_ = dds_create_writer(participant, topic, qos.get(), nullptr);
  if (hb->writer_ < 0)
    return Error{fmt::format("Cyclone writer {}: {}", topics::kHeartbeat.name, dds_strretcode(hb->writer_))};
  hb->counters_ = &counters;
  hb->identity_ = ServiceIdentity::of(std::move(service));
  hb->publish();
  hb->ticker_ = std::make_unique<PeriodicTask>(period, [p = hb.get()] { p->publish(); });
  return hb;
}

CycloneHeartbeat::~CycloneHeartbeat() { ticker_.reset(); }

void CycloneHeartbeat::set_state(slam_ServiceState state) {
  state_ = state;
  publish();
}

void CycloneHeartbeat::publish() {
  std::lock_guard lock(publish_mutex_);
  const auto counters = counters_->snapshot();
  counter_samples_.resize(counters.size());
  for (size_t i = 0; i < counters.size(); ++i) {
    copy_bounded(counters[i].first, counter_samples_[i].name, sizeof counter_samples_[i].name);
    counter_samples_[i].value = counters[i].second;
  }
  slam_Heartbeat sample{};
  copy_bounded(identity_.service, sample.service, sizeof sample.service);
  copy_bounded(identity_.instance_id, sample.instance_id, sizeof sample.instance_id);
  sample.pid = identity_.pid;
  copy_bounded(identity_.host, sample.host, sizeof sample.host);
  sample.stamp_ns = now_ns();
  sample.uptime_s = identity_.uptime_s();
  sample.state = state_.load();
  sample.counters = {static_cast<uint32_t>(counter_samples_.size()), static_cast<uint32_t>(counter_samples_.size()),
                     counter_samples_.data(), false};
  const dds_return_t rc = dds_write(writer_, &sample);
  if (rc != DDS_RETCODE_OK) spdlog::warn("writing {}: {}", topics::kHeartbeat.name, dds_strretcode(rc));
}


}  // namespace slam::sim
