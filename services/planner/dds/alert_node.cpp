// AlertNode: facts from DDS into the AlertMonitor, its changes back out.
#include "planner/dds/alert_node.hpp"

#include "common/core/clock.hpp"
#include "common/core/log.hpp"
#include "common/fastdds/fleet_messages.hpp"

namespace slam::planner {

AlertNode::AlertNode(const AlertConfig& config, std::string self, Counters& counters)
    : self_(std::move(self)),
      raised_(counters.get("alerts_raised")),
      active_(counters.get("alerts_active")),
      sent_home_(counters.get("robots_sent_home")),
      write_failures_(counters.get("alert_write_failures")),
      monitor_(config) {}

Result<std::unique_ptr<AlertNode>> AlertNode::create(dds::Participant& participant, const AlertConfig& config,
                                                     std::string self, Counters& counters) {
  std::unique_ptr<AlertNode> node(new AlertNode(config, std::move(self), counters));
  auto alerts = dds::make_writer(participant, dds::kAlert);
  if (!alerts) return alerts.error();
  node->alert_writer_ = std::move(*alerts);
  auto goals = dds::make_writer(participant, dds::kNavGoal);
  if (!goals) return goals.error();
  node->goal_writer_ = std::move(*goals);
  AlertNode* n = node.get();
  auto beats = dds::make_reader(participant, dds::kHeartbeat, [n](const slam::Heartbeat& h, const auto&) {
    std::lock_guard lock(n->mutex_);
    n->monitor_.heartbeat(h.service().to_string(), h.instance_id().to_string(),
                          h.state() == slam::SERVICE_STOPPING, monotonic_ns());
  });
  if (!beats) return beats.error();
  node->heartbeat_reader_ = std::move(*beats);
  return node;
}

void AlertNode::on_state(const slam::RobotState& state) {
  const std::string id = state.robot_id().to_string();
  std::lock_guard lock(mutex_);
  if (record_stamps_.judge(id, state.last_seen_ns()) != LatestStamps::Verdict::Fresh) return;
  monitor_.robot(id, state.presence() == slam::PRESENCE_ONLINE, state.battery());
}

void AlertNode::on_correction(const slam::PoseCorrection& correction) {
  std::lock_guard lock(mutex_);
  monitor_.robot_lost(correction.robot_id().to_string(), correction.placement() == slam::PLACEMENT_LOST);
}

void AlertNode::forget_robot(const std::string& robot_id) {
  std::lock_guard lock(mutex_);
  record_stamps_.forget(robot_id);
  monitor_.forget_robot(robot_id);
}

void AlertNode::tick(int64_t now_mono_ns, const std::function<bool(const std::string&)>& owns) {
  if (now_mono_ns < next_evaluation_ns_) return;
  next_evaluation_ns_ = now_mono_ns + kEvaluationPeriodNs;
  std::vector<AlertChange> changes;
  {
    std::lock_guard lock(mutex_);
    changes = monitor_.evaluate(now_mono_ns, now_ns(), owns);
    active_.store(static_cast<int64_t>(monitor_.active().size()), std::memory_order_relaxed);
  }
  for (const AlertChange& c : changes) {
    publish(c);
    if (c.send_home) send_home(c.subject);
  }
}

void AlertNode::publish(const AlertChange& c) {
  sample_.alert_id(c.alert_id);
  sample_.kind(msg::to_idl(c.kind));
  sample_.subject(c.subject);
  sample_.active(c.change == AlertChange::Kind::Raised);
  sample_.raised_ns(c.raised_ns);
  sample_.stamp_ns(now_ns());
  sample_.message(c.message.substr(0, 256));
  sample_.raised_by(self_);
  bool written = true;
  switch (c.change) {
    case AlertChange::Kind::Raised:
      bump(raised_);
      spdlog::warn("alert raised: {}", c.message);
      written = alert_writer_->write(sample_);
      break;
    case AlertChange::Kind::Cleared:
      spdlog::info("alert cleared: {}", c.message);
      written = alert_writer_->write(sample_);
      break;
    case AlertChange::Kind::Released:
      // Another planner owns the subject now and raises it itself; a late joiner must not get this
      // planner's copy too.
      spdlog::info("alert handed to the planner that now owns its subject: {}", c.alert_id);
      written = alert_writer_->unregister(sample_);
      break;
  }
  if (!written) bump(write_failures_);
}

void AlertNode::send_home(const std::string& robot_id) {
  slam::NavGoal goal;
  goal.robot_id(robot_id);
  goal.goal_id(goal_ids_.next());
  goal.mode(slam::GOAL_HOME);
  if (!goal_writer_->write(goal)) {
    bump(write_failures_);
    return;
  }
  bump(sent_home_);
  spdlog::warn("robot '{}' sent home: battery low", robot_id);
}

}  // namespace slam::planner
