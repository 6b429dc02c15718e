#include "common/fastdds/heartbeat.hpp"

namespace slam {

Result<std::unique_ptr<HeartbeatPublisher>> HeartbeatPublisher::start(dds::Participant& participant,
                                                                      std::string service,
                                                                      const Counters& counters,
                                                                      std::chrono::milliseconds period) {
  auto writer = dds::make_writer(participant, dds::kHeartbeat);
  if (!writer) return writer.error();
  std::unique_ptr<HeartbeatPublisher> hb(new HeartbeatPublisher());
  hb->writer_ = std::move(*writer);
  hb->loop_ = std::make_unique<HeartbeatLoop>(std::move(service), counters, period,
                                              [p = hb.get()](const HeartbeatContent& c) { p->write(c); });
  return hb;
}

void HeartbeatPublisher::write(const HeartbeatContent& content) {
  sample_.service(content.identity.service);
  sample_.instance_id(content.identity.instance_id);
  sample_.pid(content.identity.pid);
  sample_.host(content.identity.host);
  sample_.stamp_ns(content.stamp_ns);
  sample_.uptime_s(content.uptime_s);
  sample_.state(static_cast<ServiceState>(content.state));
  auto& out = sample_.counters();
  out.clear();
  for (const auto& [name, value] : content.counters) {
    Counter c;
    c.name(name);
    c.value(value);
    out.push_back(c);
  }
  writer_->write(sample_);
}

}  // namespace slam
