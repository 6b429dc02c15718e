#pragma once
// Operator alerts, plain C++: a robot gone offline, a robot with a low battery, a service whose
// heartbeats stopped without it saying it stops. The monitor keeps the latest facts (robot
// states, heartbeats) and, on evaluate(), compares what should be raised with what it raised and
// returns the changes to publish. Several planners run one each: every monitor sees every fact,
// but speaks only for the subjects its planner owns (`owns`, the planners' rendezvous ownership),
// so each alert is raised once. A subject that moves to another planner is released here (that
// planner raises it afresh) rather than cleared. Plain and single-threaded: the caller locks;
// `now_mono_ns` is monotonic, `now_wall_ns` the wall clock stamped on alerts.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/core/alert_kind.hpp"
#include "common/core/result.hpp"

namespace slam::planner {

using AlertKind = alerts::Kind;

struct AlertConfig {
  // A robot reporting a battery below this fraction (0..1) is alerted and sent home; 0 disables.
  double battery_low = 0.2;
  // The battery alert clears above battery_low + this: a level hovering at the threshold does not
  // raise, clear and send the robot home over and over.
  double battery_clear_margin = 0.05;
  // Heartbeats silent this long (s) raise "service silent" (services beat every 0.5-1 s).
  double service_silent_s = 5.0;
  // A silent service is forgotten after this long (s): its alert clears (a killed instance never
  // comes back under the same id).
  double service_forget_s = 600.0;
};

Status validate(const AlertConfig& config);

struct AlertChange {
  enum class Kind : std::uint8_t {
    Raised,
    Cleared,
    Released,  // no longer this planner's to speak for: stop publishing it, do not clear it
  };
  Kind change = Kind::Raised;
  std::string alert_id;  // "offline/ROBOT", "battery/ROBOT", "silent/SERVICE/INSTANCE"
  AlertKind kind = AlertKind::RobotOffline;
  std::string subject;  // the robot id, or SERVICE/INSTANCE
  std::string message;
  std::int64_t raised_ns = 0;  // wall clock when raised
  bool send_home = false;      // a battery alert just raised: the robot should head home
};

class AlertMonitor {
 public:
  explicit AlertMonitor(AlertConfig config = {});

  // The latest state of a robot: online or not, battery 0..1 (negative: unknown, the last known
  // level stands).
  void robot(const std::string& robot_id, bool online, float battery);
  // Whether the mapper has lost where the robot is (its PoseCorrection's placement).
  void robot_lost(const std::string& robot_id, bool lost);
  // A robot forgotten by the operator: its alerts clear at the next evaluate().
  void forget_robot(const std::string& robot_id);
  // A heartbeat of SERVICE/INSTANCE; a service that says it stops leaves without an alert.
  void heartbeat(const std::string& service, const std::string& instance, bool stopping,
                 std::int64_t now_mono_ns);

  // The key `owns` is asked about for an alert's subject: the robot id (as robots are owned), or
  // "service:SERVICE/INSTANCE".
  static std::string ownership_key(AlertKind kind, const std::string& subject);

  // What changed since the last call: alerts raised, cleared or released.
  std::vector<AlertChange> evaluate(std::int64_t now_mono_ns, std::int64_t now_wall_ns,
                                    const std::function<bool(const std::string&)>& owns);

  // Alerts raised here and not cleared, by alert id.
  const std::map<std::string, AlertChange>& active() const { return active_; }

 private:
  struct RobotFacts {
    bool online = true;
    float battery = -1.0f;
    bool battery_low = false;  // with hysteresis: set below battery_low, reset above it + margin
    bool lost = false;
  };
  struct ServiceFacts {
    std::string service;
    std::string instance;
    std::int64_t last_heard_mono_ns = 0;
  };
  struct Condition {
    AlertKind kind;
    std::string subject;
    std::string message;
  };

  // Every alert that should be active now, by alert id (before ownership).
  std::map<std::string, Condition> conditions(std::int64_t now_mono_ns) const;

  AlertConfig config_;
  std::map<std::string, RobotFacts> robots_;
  std::map<std::string, ServiceFacts> services_;  // by SERVICE/INSTANCE
  std::map<std::string, AlertChange> active_;
};

}  // namespace slam::planner
