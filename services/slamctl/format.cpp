#include "slamctl/format.hpp"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>
#include <utility>

#include "common/core/alert_kind.hpp"
#include "common/core/geometry.hpp"
#include "common/fastdds/fleet_messages.hpp"

namespace slam::ctl {
namespace {

std::string fmt(const char* f, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, f, args...);
  return buf;
}

std::string point(Vec2 p) {
  return fmt("(%.2f, %.2f)", p.x, p.y);
}

// "(x, y, theta deg)"
std::string pose_deg(const Pose& p) {
  return fmt("(%.2f, %.2f, %.1f deg)", p.x, p.y, to_degrees(p.theta));
}

}  // namespace

std::string map_result_name(MapResult result) {
  switch (result) {
    case MAP_OK:
      return "OK";
    case MAP_INVALID_REQUEST:
      return "INVALID_REQUEST";
    case MAP_IO_ERROR:
      return "IO_ERROR";
    case MAP_BAD_FILE:
      return "BAD_FILE";
    case MAP_UNKNOWN_ROBOT:
      return "UNKNOWN_ROBOT";
  }
  return "result " + std::to_string(static_cast<int>(result));
}

double age_s(int64_t stamp_ns, int64_t now_ns) {
  return static_cast<double>(now_ns - stamp_ns) * 1e-9;
}

namespace {

// Rates are shown to one decimal, or as integers once large.
std::string rate_text(double per_s) {
  return per_s >= 100.0 ? fmt("%.0f/s", per_s) : fmt("%.1f/s", per_s);
}

}  // namespace

ServiceSeen service_seen(const msg::Heartbeat& first, const msg::Heartbeat& latest) {
  ServiceSeen out{latest, {}};
  const double span_s = latest.uptime_s - first.uptime_s;
  if (span_s <= 0.0) return out;
  for (const auto& [name, value] : latest.counters) {
    for (const auto& [before_name, before] : first.counters) {
      if (before_name != name) continue;
      out.rates[name] = static_cast<double>(value - before) / span_s;
      break;
    }
  }
  return out;
}

const std::vector<std::string>& main_counters(std::string_view service) {
  static const std::map<std::string, std::vector<std::string>, std::less<>> table{
      {"gateway", {"messages_in", "observations", "commands_sent"}},
      {"mapper", {"observations", "points", "patches"}},
      {"planner", {"waypoints_sent", "paths_published", "path_requests"}},
      {"simulator", {"steps", "reports_sent", "waypoints_received"}},
      {"viewer", {"frames", "samples_received", "commands_sent"}},
  };
  static const std::vector<std::string> none;
  const auto it = table.find(service);
  return it == table.end() ? none : it->second;
}

bool is_error_counter(std::string_view name) {
  for (std::string_view bad : {"fail", "reject", "refused", "dropped", "lost", "error", "overrun", "unknown"})
    if (name.find(bad) != std::string_view::npos) return true;
  return false;
}

std::string format_service(const ServiceSeen& s, int64_t now_ns, bool verbose) {
  const msg::Heartbeat& hb = s.latest;
  std::string out =
      fmt("%-10s %-24s %-8s up %8.1f s  seen %4.1f s ago", hb.service.c_str(), hb.instance_id.c_str(),
          msg::service_state_name(hb.state), hb.uptime_s, age_s(hb.stamp_ns, now_ns));
  for (const std::string& name : main_counters(hb.service)) {
    const auto rate = s.rates.find(name);
    if (rate != s.rates.end()) out += "  " + name + " " + rate_text(rate->second);
  }
  std::string errors;
  for (const auto& [name, value] : hb.counters)
    if (value != 0 && is_error_counter(name))
      errors += fmt(" %s %lld", name.c_str(), static_cast<long long>(value));
  if (!errors.empty()) out += "  errors:" + errors;
  out += "\n";
  if (!verbose) return out;
  for (const auto& [name, value] : hb.counters) {
    const auto rate = s.rates.find(name);
    out += fmt("    %-32s %12lld", name.c_str(), static_cast<long long>(value));
    if (rate != s.rates.end()) out += "  " + rate_text(rate->second);
    out += "\n";
  }
  return out;
}

std::string services_json(const std::vector<ServiceSeen>& services, int64_t now_ns) {
  nlohmann::json out = nlohmann::json::array();
  for (const ServiceSeen& s : services) {
    const msg::Heartbeat& hb = s.latest;
    nlohmann::json counters = nlohmann::json::object();
    nlohmann::json errors = nlohmann::json::object();
    for (const auto& [name, value] : hb.counters) {
      counters[name] = value;
      if (value != 0 && is_error_counter(name)) errors[name] = value;
    }
    out.push_back({{"service", hb.service},
                   {"instance", hb.instance_id},
                   {"pid", hb.pid},
                   {"host", hb.host},
                   {"state", msg::service_state_name(hb.state)},
                   {"uptime_s", hb.uptime_s},
                   {"seen_s_ago", age_s(hb.stamp_ns, now_ns)},
                   {"rates", s.rates},
                   {"errors", errors},
                   {"counters", counters}});
  }
  return out.dump(2) + "\n";
}

std::string robots_json(const std::vector<RobotSeen>& robots, int64_t now_ns) {
  nlohmann::json out = nlohmann::json::array();
  for (const RobotSeen& r : robots) {
    const msg::RobotState& s = r.state;
    nlohmann::json robot{{"id", s.robot_id},
                         {"presence", s.online ? "online" : "offline"},
                         {"protocol", s.protocol_v2 ? "v2" : "v1"},
                         {"x", s.pose.x},
                         {"y", s.pose.y},
                         {"theta", s.has_heading ? nlohmann::json(s.pose.theta) : nlohmann::json(nullptr)},
                         {"battery", s.battery < 0.0f ? nlohmann::json(nullptr) : nlohmann::json(s.battery)},
                         {"status", s.status},
                         {"seen_s_ago", age_s(s.last_seen_ns, now_ns)},
                         {"messages", s.messages},
                         {"points", s.points},
                         {"rejected", s.rejected},
                         {"goal", nullptr},
                         {"correction", nullptr}};
    if (r.path) {
      robot["goal"] = {{"goal_id", r.path->goal_id},
                       {"mode", msg::goal_mode_name(r.path->mode)},
                       {"status", msg::goal_status_name(r.path->status)},
                       {"target", {r.path->target.x, r.path->target.y}},
                       {"reason", r.path->reason}};
    }
    if (r.correction) {
      const msg::PoseCorrection& c = *r.correction;
      robot["correction"] = {{"x", c.map_from_odom.x},
                             {"y", c.map_from_odom.y},
                             {"theta_deg", to_degrees(c.map_from_odom.theta)},
                             {"version", c.version},
                             {"keyframes", c.keyframes},
                             {"loop_closures", c.loop_closures},
                             {"sigma_m", position_sigma(c.covariance)},
                             {"source", msg::correction_source_id(c.source)},
                             {"placement", msg::robot_placement_name(c.placement)},
                             {"localisation_score", c.localisation_score}};
    }
    out.push_back(std::move(robot));
  }
  return out.dump(2) + "\n";
}

std::string format_alert(const msg::Alert& a, int64_t now_ns) {
  return fmt("%-7s %-14s %-32s raised %6.1f s ago by %s: %s\n", a.active ? "ACTIVE" : "cleared",
             alerts::kind_name(a.kind), a.subject.c_str(), age_s(a.raised_ns, now_ns), a.raised_by.c_str(),
             a.message.c_str());
}

std::string alerts_json(const std::vector<msg::Alert>& alerts, int64_t now_ns) {
  nlohmann::json out = nlohmann::json::array();
  for (const msg::Alert& a : alerts) {
    out.push_back({{"id", a.alert_id},
                   {"kind", alerts::kind_name(a.kind)},
                   {"subject", a.subject},
                   {"active", a.active},
                   {"raised_ns", a.raised_ns},
                   {"raised_s_ago", age_s(a.raised_ns, now_ns)},
                   {"changed_ns", a.stamp_ns},
                   {"raised_by", a.raised_by},
                   {"message", a.message}});
  }
  return out.dump(2) + "\n";
}

std::string format_correction(const msg::PoseCorrection& c) {
  // An unplaced robot says so first: its pose is its odometry's until the map search finds it.
  const std::string placement =
      c.placement == msg::RobotPlacement::Placed
          ? ""
          : fmt("%s (score %.2f) ", msg::robot_placement_name(c.placement), c.localisation_score);
  return fmt("%s%s ±%.0f cm version %llu keyframes %u loops %u %s", placement.c_str(),
             pose_deg(c.map_from_odom).c_str(), 100.0 * position_sigma(c.covariance),
             static_cast<unsigned long long>(c.version), c.keyframes, c.loop_closures,
             msg::correction_source_id(c.source));
}

std::string format_robot(const msg::RobotState& s, const msg::PoseCorrection* correction,
                         const msg::RobotPath* path, int64_t now_ns) {
  const std::string mode =
      path ? std::string(msg::goal_mode_name(path->mode)) + "/" + msg::goal_status_name(path->status) : "-";
  const std::string corrected = correction ? format_correction(*correction) : "-";
  return fmt(
      "%-16s %-7s %-3s x %8.2f  y %8.2f  %s  seen %6.1f s ago  msgs %llu  pts %llu  rejected %llu  %s  "
      "correction %s\n",
      s.robot_id.c_str(), s.online ? "online" : "offline", s.protocol_v2 ? "v2" : "v1", s.pose.x, s.pose.y,
      s.has_heading ? fmt("th %6.2f", s.pose.theta).c_str() : "th      -", age_s(s.last_seen_ns, now_ns),
      static_cast<unsigned long long>(s.messages), static_cast<unsigned long long>(s.points),
      static_cast<unsigned long long>(s.rejected), mode.c_str(), corrected.c_str());
}

std::string format_path_reply(const msg::PathReply& r) {
  std::string out = fmt("%s  length %.2f m  %zu points  planned in %.1f ms", msg::plan_status_name(r.status),
                        r.length_m, r.path.size(), r.planning_time_s * 1e3);
  if (!r.reason.empty()) out += "  (" + r.reason + ")";
  out += "\n";
  for (const Vec2& p : r.path) out += "  " + point(p) + "\n";
  return out;
}

std::string describe(const RobotObservation& s) {
  std::string line =
      fmt("observation %s seq %llu pose (%.2f, %.2f, %s) hits %zu misses %zu", s.robot_id().c_str(),
          static_cast<unsigned long long>(s.seq()), s.pose().x(), s.pose().y(),
          s.has_heading() ? fmt("%.2f", s.pose().theta()).c_str() : "-", s.hits().size(), s.misses().size());
  if (s.robot_stamp_ns() != 0)
    line += fmt(" robot stamp %.6f s", static_cast<double>(s.robot_stamp_ns()) * 1e-9);
  return line;
}
std::string describe(const RobotObservationBatch& s) {
  std::string out = fmt("observations of gateway %s batch %llu: %zu", s.gateway_id().c_str(),
                        static_cast<unsigned long long>(s.batch_seq()), s.observations().size());
  for (const RobotObservation& o : s.observations()) out += "\n  " + describe(o);
  return out;
}
std::string describe(const RobotState& s) {
  return "state " + format_robot(msg::from_idl(s), nullptr, nullptr, s.last_seen_ns());
}
std::string describe(const RobotOdometry& s) {
  return fmt("odometry %s (%.2f, %.2f, %s) correction version %llu", s.robot_id().c_str(), s.odom_pose().x(),
             s.odom_pose().y(), s.has_heading() ? fmt("%.2f", s.odom_pose().theta()).c_str() : "-",
             static_cast<unsigned long long>(s.correction_version()));
}
std::string describe(const PoseCorrection& s) {
  return "correction " + s.robot_id().to_string() + " " + format_correction(msg::from_idl(s));
}
std::string describe(const InitialPose& s) {
  return fmt("initial pose %llu %s %s", static_cast<unsigned long long>(s.request_id()), s.robot_id().c_str(),
             pose_deg(msg::from_idl(s.pose())).c_str());
}
std::string describe(const GridSnapshot& s) {
  return fmt("snapshot layout %u version %llu %ux%u cells at %.3f m, origin (%.2f, %.2f), inflation %.2f m",
             s.layout_id(), static_cast<unsigned long long>(s.version()), s.info().width(), s.info().height(),
             s.info().resolution(), s.info().origin().x(), s.info().origin().y(),
             s.info().inflation_radius());
}
std::string describe(const GridTiles& s) {
  return fmt("patch layout %u version %llu %zu tiles of %u cells, %zu octets %s", s.layout_id(),
             static_cast<unsigned long long>(s.version()), s.tiles().size(), s.tile_side(), s.data().size(),
             s.encoding() == 0   ? "raw"
             : s.encoding() == 1 ? "run-length"
             : s.encoding() == 2 ? "run-length of the XOR"
                                 : "unknown encoding");
}
std::string describe(const RobotPath& s) {
  return fmt("path %s goal %llu %s/%s target %s waypoint %u of %zu %s", s.robot_id().c_str(),
             static_cast<unsigned long long>(s.goal_id()), msg::goal_mode_name(msg::from_idl(s.mode())),
             msg::goal_status_name(msg::from_idl(s.status())), point(msg::from_idl(s.target())).c_str(),
             s.current(), s.waypoints().size(), s.reason().c_str());
}
std::string describe(const WaypointCommand& s) {
  return fmt("waypoint %s seq %llu %s (%zu more)", s.robot_id().c_str(),
             static_cast<unsigned long long>(s.seq()), point(msg::from_idl(s.waypoint())).c_str(),
             s.remaining().size());
}
std::string describe(const NavGoal& s) {
  return fmt("goal %s id %llu %s target %s", s.robot_id().c_str(),
             static_cast<unsigned long long>(s.goal_id()), msg::goal_mode_name(msg::from_idl(s.mode())),
             point(msg::from_idl(s.target())).c_str());
}
std::string describe(const MqttTraffic& s) {
  std::string hex;
  for (size_t i = 0; i < s.payload().size() && i < 16; ++i) hex += fmt("%02x", s.payload()[i]);
  return fmt("mqtt %s %s %u bytes %s%s", s.direction() == MQTT_INBOUND ? "in " : "out", s.topic().c_str(),
             s.payload_size(), hex.c_str(), s.payload_size() > 16 ? "..." : "");
}
std::string describe(const SimGroundTruth& s) {
  std::string out = fmt("ground truth %zu robots%s", s.robots().size(), s.paused() ? " (paused)" : "");
  for (const auto& r : s.robots())
    out += fmt("  %s (%.2f, %.2f)", r.robot_id().c_str(), r.true_pose().x(), r.true_pose().y());
  return out;
}
std::string describe(const Heartbeat& s) {
  return fmt("heartbeat %s %s up %.1f s, %zu counters", s.service().c_str(), s.instance_id().c_str(),
             s.uptime_s(), s.counters().size());
}
std::string describe(const MapReply& s) {
  return fmt("map reply %llu %s %s", static_cast<unsigned long long>(s.request_id()),
             map_result_name(s.result()).c_str(), s.message().c_str());
}
std::string describe(const Alert& s) {
  std::string line = format_alert(msg::from_idl(s), s.stamp_ns());
  line.pop_back();  // echo ends each sample's line itself
  return "alert " + s.alert_id().to_string() + " " + line;
}
std::string describe(const ForgetRobot& s) {
  return fmt("forget %llu %s", static_cast<unsigned long long>(s.request_id()), s.robot_id().c_str());
}
std::string describe(const FleetDigest& s) {
  const auto online = std::count_if(s.robots().begin(), s.robots().end(),
                                    [](const DigestRobot& r) { return r.presence() == PRESENCE_ONLINE; });
  return fmt("digest of gateway %s: %zu robots, %zu online", s.gateway_id().c_str(), s.robots().size(),
             static_cast<size_t>(online));
}
std::string describe(const FleetPoints& s) {
  size_t points = 0;
  for (const DigestRobotPoints& r : s.robots()) points += r.points().size();
  return fmt("points of gateway %s: %zu robots, %zu points", s.gateway_id().c_str(), s.robots().size(),
             points);
}
std::string describe(const PathReply& s) {
  return fmt("path reply %llu %s", static_cast<unsigned long long>(s.request_id()),
             format_path_reply(msg::from_idl(s)).c_str());
}

}  // namespace slam::ctl
