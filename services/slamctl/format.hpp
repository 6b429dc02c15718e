#pragma once
// slamctl's text side, plain C++: formatting what it heard as the lines a person reads and as JSON.
// The listings work on the fleet's plain messages (common/core/fleet_messages.hpp, which also names
// goal modes and statuses); `describe` (slamctl echo) takes any sample as the generated value type.
// No DDS entities here.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/fleet_messages.hpp"
#include "common/fastdds/fast_topics.hpp"

namespace slam::ctl {

std::string map_result_name(MapResult result);

// Seconds since a *_ns stamp, for "last seen 1.2 s ago".
double age_s(int64_t stamp_ns, int64_t now_ns);

// A service as `slamctl status` heard it: its latest heartbeat, and each counter's rate per second
// between the first and the latest heartbeat heard (none when only one was heard).
struct ServiceSeen {
  msg::Heartbeat latest;
  std::map<std::string, double> rates;
};
ServiceSeen service_seen(const msg::Heartbeat& first, const msg::Heartbeat& latest);
// The counters whose rates tell whether a service works (gateway: messages_in, ...); empty for a
// service not in the table.
const std::vector<std::string>& main_counters(std::string_view service);
// Counters that count something going wrong (failures, rejections, drops, losses, errors).
bool is_error_counter(std::string_view name);
// One line: service, instance, state, uptime, last heard, main rates, non-zero error counters;
// verbose: then every counter on a line of its own, with its rate when known.
std::string format_service(const ServiceSeen& s, int64_t now_ns, bool verbose);
std::string services_json(const std::vector<ServiceSeen>& services, int64_t now_ns);

// A robot as `slamctl robots` saw it.
struct RobotSeen {
  msg::RobotState state;
  std::optional<msg::PoseCorrection> correction;
  std::optional<msg::RobotPath> path;
};
std::string robots_json(const std::vector<RobotSeen>& robots, int64_t now_ns);

// One line: ACTIVE/cleared, kind, subject, age, who raised it, the message.
std::string format_alert(const msg::Alert& a, int64_t now_ns);
std::string alerts_json(const std::vector<msg::Alert>& alerts, int64_t now_ns);
// "(x, y, theta deg) version V keyframes K loops L SOURCE": a robot's map <- odom correction.
std::string format_correction(const msg::PoseCorrection& c);
// One line per robot: its state (pose in the map frame), its goal and its correction ("-" when none
// is known: the gateway then uses the identity).
std::string format_robot(const msg::RobotState& state, const msg::PoseCorrection* correction,
                         const msg::RobotPath* path, int64_t now_ns);
std::string format_path_reply(const msg::PathReply& reply);

// One line per sample for `slamctl echo TOPIC`; long sequences are summarised.
std::string describe(const RobotObservation& s);
// One line for the batch, then one per observation, indented.
std::string describe(const RobotObservationBatch& s);
std::string describe(const RobotState& s);
std::string describe(const RobotOdometry& s);
std::string describe(const PoseCorrection& s);
std::string describe(const InitialPose& s);
std::string describe(const GridSnapshot& s);
std::string describe(const GridTiles& s);
std::string describe(const RobotPath& s);
std::string describe(const WaypointCommand& s);
std::string describe(const NavGoal& s);
std::string describe(const MqttTraffic& s);
std::string describe(const SimGroundTruth& s);
std::string describe(const Heartbeat& s);
std::string describe(const MapReply& s);
std::string describe(const PathReply& s);
std::string describe(const Alert& s);
std::string describe(const ForgetRobot& s);
std::string describe(const FleetDigest& s);
std::string describe(const FleetPoints& s);

}  // namespace slam::ctl
