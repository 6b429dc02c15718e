// AlertMonitor: facts in, alert changes out.
#include "planner/core/alert_monitor.hpp"

#include <cmath>
#include <cstdio>

namespace slam::planner {

namespace {

int64_t to_ns(double seconds) {
  return static_cast<int64_t>(seconds * 1e9);
}

std::string percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f %%", fraction * 100.0);
  return buf;
}

}  // namespace

Status validate(const AlertConfig& c) {
  if (!std::isfinite(c.battery_low) || c.battery_low < 0.0 || c.battery_low >= 1.0)
    return Error{"alerts.battery_low must be a fraction in [0, 1) (0 disables battery alerts)"};
  if (!std::isfinite(c.battery_clear_margin) || c.battery_clear_margin < 0.0 || c.battery_clear_margin > 0.5)
    return Error{"alerts.battery_clear_margin must be between 0 and 0.5"};
  if (!std::isfinite(c.service_silent_s) || c.service_silent_s < 1.0 || c.service_silent_s > 3600.0)
    return Error{"alerts.service_silent_s must be between 1 and 3600"};
  if (!std::isfinite(c.service_forget_s) || c.service_forget_s <= c.service_silent_s)
    return Error{"alerts.service_forget_s must be longer than alerts.service_silent_s"};
  return Status::ok();
}

AlertMonitor::AlertMonitor(AlertConfig config) : config_(config) {}

void AlertMonitor::robot(const std::string& robot_id, bool online, float battery) {
  RobotFacts& r = robots_[robot_id];
  r.online = online;
  // A status without a battery (the last will, a v1 robot) says nothing about it: the last known
  // level stands.
  if (battery < 0.0f) return;
  r.battery = battery;
  if (config_.battery_low <= 0.0) {
    r.battery_low = false;
  } else if (battery < config_.battery_low) {
    r.battery_low = true;
  } else if (battery >= config_.battery_low + config_.battery_clear_margin) {
    r.battery_low = false;
  }
}

void AlertMonitor::robot_lost(const std::string& robot_id, bool lost) {
  robots_[robot_id].lost = lost;
}

void AlertMonitor::forget_robot(const std::string& robot_id) {
  robots_.erase(robot_id);
}

void AlertMonitor::heartbeat(const std::string& service, const std::string& instance, bool stopping,
                             int64_t now_mono_ns) {
  const std::string subject = service + "/" + instance;
  if (stopping) {
    services_.erase(subject);
    return;
  }
  services_[subject] = ServiceFacts{service, instance, now_mono_ns};
}

std::string AlertMonitor::ownership_key(AlertKind kind, const std::string& subject) {
  return kind == AlertKind::ServiceSilent ? "service:" + subject : subject;
}

std::map<std::string, AlertMonitor::Condition> AlertMonitor::conditions(int64_t now_mono_ns) const {
  std::map<std::string, Condition> out;
  for (const auto& [id, r] : robots_) {
    if (!r.online)
      out.emplace("offline/" + id, Condition{AlertKind::RobotOffline, id, "robot '" + id + "' is offline"});
    if (r.lost) {
      out.emplace("lost/" + id, Condition{AlertKind::RobotLost, id,
                                          "robot '" + id +
                                              "' is lost: its scans stopped fitting the map where it "
                                              "was; it is searched for on the whole map"});
    }
    if (r.battery_low) {
      out.emplace("battery/" + id, Condition{AlertKind::BatteryLow, id,
                                             "robot '" + id + "' battery " + percent(r.battery) + " (below " +
                                                 percent(config_.battery_low) + "): sent home"});
    }
  }
  for (const auto& [subject, s] : services_) {
    const int64_t silent_ns = now_mono_ns - s.last_heard_mono_ns;
    if (silent_ns < to_ns(config_.service_silent_s)) continue;
    char since[32];
    std::snprintf(since, sizeof since, "%.0f s", config_.service_silent_s);
    out.emplace("silent/" + subject, Condition{AlertKind::ServiceSilent, subject,
                                               s.service + " '" + s.instance + "' silent for over " + since});
  }
  return out;
}

std::vector<AlertChange> AlertMonitor::evaluate(int64_t now_mono_ns, int64_t now_wall_ns,
                                                const std::function<bool(const std::string&)>& owns) {
  // Services silent past the forget time are dropped: their alerts clear below.
  std::erase_if(services_, [&](const auto& entry) {
    return now_mono_ns - entry.second.last_heard_mono_ns >= to_ns(config_.service_forget_s);
  });
  const auto wanted = conditions(now_mono_ns);
  std::vector<AlertChange> changes;
  for (auto it = active_.begin(); it != active_.end();) {
    AlertChange& a = it->second;
    const bool mine = owns(ownership_key(a.kind, a.subject));
    if (wanted.contains(it->first) && mine) {
      ++it;
      continue;
    }
    AlertChange out = a;
    out.change = mine ? AlertChange::Kind::Cleared : AlertChange::Kind::Released;
    out.send_home = false;
    changes.push_back(std::move(out));
    it = active_.erase(it);
  }
  for (const auto& [id, c] : wanted) {
    if (active_.contains(id) || !owns(ownership_key(c.kind, c.subject))) continue;
    AlertChange a{AlertChange::Kind::Raised,      id, c.kind, c.subject, c.message, now_wall_ns,
                  c.kind == AlertKind::BatteryLow};
    active_.emplace(id, a);
    changes.push_back(std::move(a));
  }
  return changes;
}

}  // namespace slam::planner
