// Mission waypoints from the command line or a YAML file, and the progress line.
#include "slamctl/mission_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/fastdds/fleet_messages.hpp"

namespace slam::ctl {
namespace {

// NavMission.waypoints' bound in nav.idl.
constexpr size_t kMaxWaypoints = 256;

Point2 point(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

Status check_count(size_t count) {
  if (count == 0) return Error{"a mission needs at least one waypoint"};
  if (count > kMaxWaypoints)
    return Error{"a mission has at most " + std::to_string(kMaxWaypoints) + " waypoints, got " +
                 std::to_string(count)};
  return Status::ok();
}

std::string fixed(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v);
  return text;
}

}  // namespace

Result<std::vector<Point2>> waypoints_from_numbers(const std::vector<double>& xy) {
  if (xy.size() % 2 != 0) return Error{"waypoints are x y pairs: got an odd count of numbers"};
  SLAM_TRY(check_count(xy.size() / 2));
  std::vector<Point2> out;
  for (size_t i = 0; i < xy.size(); i += 2) {
    if (!std::isfinite(xy[i]) || !std::isfinite(xy[i + 1]))
      return Error{"waypoint " + std::to_string(i / 2) + " is not finite"};
    out.push_back(point(xy[i], xy[i + 1]));
  }
  return out;
}

Result<MissionSpec> parse_mission_file(std::string_view yaml) {
  YAML::Node doc;
  try {
    doc = YAML::Load(std::string(yaml));
  } catch (const YAML::Exception& e) {
    return Error{std::string("not valid YAML: ") + e.msg};
  }
  if (!doc.IsMap()) return Error{"must be a map with \"waypoints\" (and \"loop\")"};
  MissionSpec out;
  for (const auto& entry : doc) {
    const std::string key = entry.first.Scalar();
    if (key != "waypoints" && key != "loop") return Error{"unknown key \"" + key + "\" (waypoints, loop)"};
  }
  if (const YAML::Node loop = doc["loop"]) {
    try {
      out.loop = loop.as<bool>();
    } catch (const YAML::Exception&) {
      return Error{"\"loop\" must be true or false"};
    }
  }
  const YAML::Node waypoints = doc["waypoints"];
  if (!waypoints || !waypoints.IsSequence()) return Error{"\"waypoints\" must be a list of [x, y]"};
  SLAM_TRY(check_count(waypoints.size()));
  for (size_t i = 0; i < waypoints.size(); ++i) {
    const YAML::Node p = waypoints[i];
    const std::string where = "waypoints[" + std::to_string(i) + "]";
    if (!p.IsSequence() || p.size() != 2) return Error{where + " must be [x, y] in metres"};
    double x = 0.0;
    double y = 0.0;
    try {
      x = p[0].as<double>();
      y = p[1].as<double>();
    } catch (const YAML::Exception&) {
      return Error{where + " must be [x, y] in metres"};
    }
    if (!std::isfinite(x) || !std::isfinite(y)) return Error{where + " is not finite"};
    out.waypoints.push_back(point(x, y));
  }
  return out;
}

Result<MissionSpec> load_mission_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Error{"mission file " + path + ": cannot be read"};
  std::ostringstream text;
  text << in.rdbuf();
  auto spec = parse_mission_file(text.str());
  if (!spec) return Error{"mission file " + path + ": " + spec.message()};
  return spec;
}

bool mission_behind(const NavMission& next, const NavMission& kept) {
  if (next.mission_id() != kept.mission_id()) return false;
  if ((next.status() == MISSION_ACTIVE) != (kept.status() == MISSION_ACTIVE))
    return next.status() == MISSION_ACTIVE;
  return next.laps() < kept.laps() || (next.laps() == kept.laps() && next.current() < kept.current());
}

std::string format_mission(const NavMission& m) {
  std::string line = m.robot_id().to_string() + " mission " + std::to_string(m.mission_id()) + ": " +
                     msg::mission_status_name(msg::from_idl(m.status()));
  const auto& wps = m.waypoints();
  if (m.current() < wps.size()) {
    const Point2& p = wps[m.current()];
    line += ", waypoint " + std::to_string(m.current() + 1) + "/" + std::to_string(wps.size()) + " (" +
            fixed(p.x()) + ", " + fixed(p.y()) + ")";
  }
  line += ", " + std::to_string(m.laps()) + " lap(s) done, " + (m.loop() ? "looped" : "once");
  if (m.reason().size() > 0) line += "; " + m.reason().to_string();
  return line + "\n";
}

}  // namespace slam::ctl
