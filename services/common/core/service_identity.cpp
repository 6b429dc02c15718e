#include "common/core/service_identity.hpp"

#include <unistd.h>

#include "common/core/clock.hpp"

namespace slam {

ServiceIdentity ServiceIdentity::of(std::string service) {
  ServiceIdentity id;
  id.service = std::move(service);
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  id.host = host;
  id.pid = static_cast<uint32_t>(getpid());
  id.instance_id = id.host + ":" + std::to_string(id.pid);
  id.started = std::chrono::steady_clock::now();
  return id;
}

double ServiceIdentity::uptime_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

PeriodicTask::PeriodicTask(std::chrono::milliseconds period, std::function<void()> tick) {
  thread_ = std::thread([this, period, tick = std::move(tick)] {
    auto next = std::chrono::steady_clock::now() + period;
    // Short sleeps so destruction is prompt whatever the period.
    while (!stop_) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (std::chrono::steady_clock::now() < next) continue;
      next += period;
      tick();
    }
  });
}

PeriodicTask::~PeriodicTask() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

HeartbeatLoop::HeartbeatLoop(std::string service, const Counters& counters, std::chrono::milliseconds period,
                             Write write)
    : identity_(ServiceIdentity::of(std::move(service))), counters_(counters), write_(std::move(write)) {
  publish();
  ticker_ = std::make_unique<PeriodicTask>(period, [this] { publish(); });
}

void HeartbeatLoop::set_state(uint32_t state) {
  state_ = state;
  publish();
}

void HeartbeatLoop::publish() {
  std::lock_guard lock(publish_mutex_);
  const auto counters = counters_.snapshot();
  write_(HeartbeatContent{identity_, now_ns(), identity_.uptime_s(), state_.load(), counters});
}

}  // namespace slam
