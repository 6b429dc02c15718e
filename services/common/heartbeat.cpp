#include "common/heartbeat.hpp"

#include <unistd.h>

#include "common/clock.hpp"

namespace slam {

Result<std::unique_ptr<HeartbeatPublisher>> HeartbeatPublisher::start(dds::Participant& participant, std::string service,
                                                                      const Counters& counters,
                                                                      std::chrono::milliseconds period) {
  auto writer = dds::make_writer(participant, dds::kHeartbeat);
  if (!writer) return Error{writer.message()};
  std::unique_ptr<HeartbeatPublisher> hb(new HeartbeatPublisher());
  hb->writer_ = std::move(*writer);
  hb->counters_ = &counters;
  hb->service_ = std::move(service);
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  hb->host_ = host;
  hb->instance_id_ = hb->host_ + ":" + std::to_string(getpid());
  hb->period_ = period;
  hb->started_ = std::chrono::steady_clock::now();
  hb->publish();
  hb->thread_ = std::thread([p = hb.get()] { p->run(); });
  return hb;
}

HeartbeatPublisher::~HeartbeatPublisher() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void HeartbeatPublisher::set_state(ServiceState state) {
  state_ = state;
  publish();
}

void HeartbeatPublisher::publish() {
  std::lock_guard lock(publish_mutex_);
  sample_.service(service_);
  sample_.instance_id(instance_id_);
  sample_.pid(static_cast<uint32_t>(getpid()));
  sample_.host(host_);
  sample_.stamp_ns(now_ns());
  sample_.uptime_s(std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count());
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

void HeartbeatPublisher::run() {
  auto next = std::chrono::steady_clock::now() + period_;
  while (!stop_) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (std::chrono::steady_clock::now() < next) continue;
    next += period_;
    publish();
  }
}

}  // namespace slam
