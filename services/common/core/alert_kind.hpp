#pragma once
// The kinds of operator alert, in the order of the IDL enum AlertKind (system.idl), for the
// transport-free cores and the tools: the one place their names are spelled.
#include <cstdint>

namespace slam::alerts {

enum class Kind : std::uint8_t { RobotOffline, ServiceSilent, BatteryLow, RobotLost };

// For people: "robot offline", "service silent", "battery low", "robot lost".
constexpr const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::RobotOffline:
      return "robot offline";
    case Kind::ServiceSilent:
      return "service silent";
    case Kind::BatteryLow:
      return "battery low";
    case Kind::RobotLost:
      return "robot lost";
  }
  return "unknown alert";  // a kind from a newer peer
}

// For machine-readable output (JSON): "robot_offline", "service_silent", "battery_low", "robot_lost".
constexpr const char* kind_id(Kind kind) {
  switch (kind) {
    case Kind::RobotOffline:
      return "robot_offline";
    case Kind::ServiceSilent:
      return "service_silent";
    case Kind::BatteryLow:
      return "battery_low";
    case Kind::RobotLost:
      return "robot_lost";
  }
  return "unknown";
}

}  // namespace slam::alerts
