#include "common/fastdds/heartbeat.hpp"

#include "common/core/clock.hpp"

namespace slam {

Result<std::unique_ptr<HeartbeatPublisher>> HeartbeatPublisher::start(dds::Participant& participant,
                                                                      std::string service,
                                                                      const Counters& counters,
                                                                      std::chrono::milliseconds period) {
  auto writer = dds::make_writer(participant, dds::kHeartbeat);
  if (!writer) return writer.error();
  std::unique_ptr<HeartbeatPublisher> hb(new HeartbeatPublisher());
  hb->writer_ = std::move(*writer);
  hb->counters_ = &counters;
  hb->identity_ = ServiceIdentity::of(std::move(service));
  hb->publish();
  hb->ticker_ = std::make_unique<PeriodicTask>(period, [p = hb.get()] { p->publish(); });
  return hb;
}

HeartbeatPublisher::~HeartbeatPublisher() {
  ticker_.reset();
}

void HeartbeatPublisher::set_state(ServiceState state) {
  state_ = state;
  publish();
}

void HeartbeatPublisher::publish() {
  std::lock_guard lock(publish_mutex_);
  sample_.service(identity_.service);
  sample_.instance_id(identity_.instance_id);
  sample_.pid(identity_.pid);
  sample_.host(identity_.host);
  sample_.stamp_ns(now_ns());
  sample_.uptime_s(identity_.uptime_s());
  sample_.state(state_.load());
  auto& out = sample_.counters();
  out.clear();
  for (const auto& [name, value] : counters_->snapshot()) {
    Counter c;
    c.name(name);
    c.value(value);
    out.push_back(c);
  }
  writer_->write(sample_);
}

}  // namespace slam
