// GatewayIntake: the locked hand-over from the MQTT thread and the DDS reader threads to the loop.
#include "gateway/core/gateway_intake.hpp"

#include <utility>

namespace slam::gateway {

bool GatewayInputs::empty() const {
  return inbound.empty() && corrections.empty() && waypoints.empty() && requests.empty() &&
         heartbeats.empty() && protocols.empty() && forgets.empty();
}

void GatewayIntake::push(InboundMessage& message) {
  bool notify = false;
  {
    std::unique_lock lock(mutex_);
    room_.wait(lock, [this] { return closed_ || pending_.inbound.size() < max_inbound_; });
    pending_points_ += message.points();
    pending_.inbound.push_back(std::move(message));
    if (!spare_.empty()) {
      message = std::move(spare_.back());
      spare_.pop_back();
    }
    notify = take_notify();
  }
  if (notify) wake_.notify_one();
}

void GatewayIntake::push(CorrectionInput input) {
  std::lock_guard lock(mutex_);
  pending_.corrections.push_back(std::move(input));
}

void GatewayIntake::push(WaypointInput input) {
  bool notify = false;
  {
    std::lock_guard lock(mutex_);
    pending_.waypoints.push_back(std::move(input));
    notify = take_notify();
  }
  if (notify) wake_.notify_one();
}

void GatewayIntake::push(MqttRequestInput input) {
  bool notify = false;
  {
    std::lock_guard lock(mutex_);
    pending_.requests.push_back(std::move(input));
    notify = take_notify();
  }
  if (notify) wake_.notify_one();
}

void GatewayIntake::push(PeerHeartbeat input) {
  std::lock_guard lock(mutex_);
  pending_.heartbeats.push_back(std::move(input));
}

void GatewayIntake::push(ProtocolReport input) {
  std::lock_guard lock(mutex_);
  pending_.protocols.push_back(std::move(input));
}

void GatewayIntake::push_forget(std::string robot_id) {
  bool notify = false;
  {
    std::lock_guard lock(mutex_);
    pending_.forgets.push_back(std::move(robot_id));
    notify = take_notify();
  }
  if (notify) wake_.notify_one();
}

bool GatewayIntake::ready() const {
  const std::size_t inbound = pending_.inbound.size();
  return !pending_.waypoints.empty() || !pending_.requests.empty() || !pending_.forgets.empty() ||
         inbound >= max_inbound_ || (inbound > 0 && inbound >= wake_on_.messages) ||
         (inbound > 0 && pending_points_ >= wake_on_.points);
}

bool GatewayIntake::take_notify() {
  if (!waiting_ || notified_ || !ready()) return false;
  notified_ = true;
  return true;
}

void GatewayIntake::wait_until(Clock::time_point deadline, InboundWake wake) {
  std::unique_lock lock(mutex_);
  wake_on_ = wake;
  waiting_ = true;
  notified_ = false;
  wake_.wait_until(lock, deadline, [this] { return ready(); });
  waiting_ = false;
}

void GatewayIntake::drain(GatewayInputs& out) {
  out.corrections.clear();
  out.waypoints.clear();
  out.requests.clear();
  out.heartbeats.clear();
  out.protocols.clear();
  out.forgets.clear();
  bool had_no_room = false;
  {
    std::lock_guard lock(mutex_);
    for (InboundMessage& m : out.inbound) spare_.push_back(std::move(m));
    out.inbound.clear();
    had_no_room = pending_.inbound.size() >= max_inbound_;
    std::swap(out, pending_);
    pending_points_ = 0;
  }
  if (had_no_room) room_.notify_all();
}

void GatewayIntake::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  room_.notify_all();
}

}  // namespace slam::gateway
