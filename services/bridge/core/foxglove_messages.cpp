// Foxglove JSON messages from the fleet model (see foxglove_messages.hpp).
#include "bridge/core/foxglove_messages.hpp"

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <vector>

#include "bridge/core/base64.hpp"
#include "common/core/cell_class.hpp"

namespace slam::bridge {
namespace {

using nlohmann::json;

json time_of(int64_t stamp_ns) {
  const int64_t ns = std::max<int64_t>(stamp_ns, 0);
  return {{"sec", ns / 1'000'000'000}, {"nsec", ns % 1'000'000'000}};
}

json vec3(double x, double y, double z) {
  return {{"x", x}, {"y", y}, {"z", z}};
}

// Rotation about +z by `theta`.
json yaw(double theta) {
  return {{"x", 0.0}, {"y", 0.0}, {"z", std::sin(theta / 2.0)}, {"w", std::cos(theta / 2.0)}};
}

json pose(double x, double y, double z, double theta = 0.0) {
  return {{"position", vec3(x, y, z)}, {"orientation", yaw(theta)}};
}

json color(const Rgba& c) {
  return {{"r", c.r}, {"g", c.g}, {"b", c.b}, {"a", c.a}};
}

// A SceneEntity with every primitive list present and empty, as the schema requires.
json entity(const std::string& id, int64_t stamp_ns) {
  const json empty = json::array();
  return {{"timestamp", time_of(stamp_ns)},
          {"frame_id", kMapFrame},
          {"id", id},
          {"lifetime", {{"sec", 0}, {"nsec", 0}}},
          {"frame_locked", false},
          {"metadata", empty},
          {"arrows", empty},
          {"cubes", empty},
          {"spheres", empty},
          {"cylinders", empty},
          {"lines", empty},
          {"triangles", empty},
          {"texts", empty},
          {"models", empty}};
}

json sphere(double x, double y, double z, double size, const Rgba& c) {
  return {{"pose", pose(x, y, z)}, {"size", vec3(size, size, size)}, {"color", color(c)}};
}

Rgba from_hsv(double hue, double saturation, double value, double alpha) {
  const double h = std::fmod(hue, 1.0) * 6.0;
  const double c = value * saturation;
  const double x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0));
  const double m = value - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0:
      r = c, g = x;
      break;
    case 1:
      r = x, g = c;
      break;
    case 2:
      g = c, b = x;
      break;
    case 3:
      g = x, b = c;
      break;
    case 4:
      r = x, b = c;
      break;
    default:
      r = c, b = x;
      break;
  }
  return {r + m, g + m, b + m, alpha};
}

const char* status_name(PathStatus s) {
  switch (s) {
    case PathStatus::Active:
      return "active";
    case PathStatus::Reached:
      return "reached";
    case PathStatus::Failed:
      return "failed";
    case PathStatus::None:
      break;
  }
  return "none";
}

constexpr uint8_t kNumericInt8 = 2;
constexpr uint8_t kNumericFloat32 = 7;
constexpr uint8_t kLineStrip = 0;

}  // namespace

Rgba robot_color(const std::string& robot_id) {
  uint32_t hash = 2166136261u;  // FNV-1a
  for (const char ch : robot_id) hash = (hash ^ static_cast<uint8_t>(ch)) * 16777619u;
  return from_hsv((hash % 360) / 360.0, 0.75, 0.95, 1.0);
}

int8_t occupancy_of(uint8_t cell) {
  if ((cell & kCellObstructed) != 0) return 100;
  switch (cell & kCellStateMask) {
    case kCellOccupied:
      return 100;
    case kCellFree:
      return (cell & kCellInflated) != 0 ? 50 : 0;
    default:
      return -1;
  }
}

std::string grid_message(const GridGeometry& geometry, std::span<const uint8_t> cells, const CellBox& box,
                         int64_t stamp_ns) {
  std::vector<uint8_t> bytes(box.cells());
  size_t k = 0;
  for (int32_t y = box.y0; y < box.y0 + box.height; ++y) {
    const uint8_t* row = cells.data() + geometry.index(Cell{box.x0, y});
    for (int32_t x = 0; x < box.width; ++x) bytes[k++] = static_cast<uint8_t>(occupancy_of(row[x]));
  }
  const Vec2 corner = geometry.corner(Cell{box.x0, box.y0});
  const json message = {
      {"timestamp", time_of(stamp_ns)},
      {"frame_id", kMapFrame},
      {"pose", pose(corner.x, corner.y, 0.0)},
      {"column_count", box.width},
      {"cell_size", {{"x", geometry.resolution}, {"y", geometry.resolution}}},
      {"row_stride", box.width},
      {"cell_stride", 1},
      {"fields", json::array({{{"name", "occupancy"}, {"offset", 0}, {"type", kNumericInt8}}})},
      {"data", base64(bytes)}};
  return message.dump();
}

std::string robots_message(const FleetModel& fleet, int64_t stamp_ns) {
  json entities = json::array();
  for (const auto& [id, r] : fleet.robots()) {
    if (!r.has_state) continue;
    Rgba c = robot_color(id);
    if (!r.state.online) c.a = 0.35;
    const Pose& p = r.state.pose;
    json e = entity("robot/" + id, stamp_ns);
    e["metadata"] = json::array({{{"key", "robot_id"}, {"value", id}},
                                 {{"key", "online"}, {"value", r.state.online ? "true" : "false"}}});
    if (r.state.has_heading)
      e["arrows"] = json::array({{{"pose", pose(p.x, p.y, 0.05, p.theta)},
                                  {"shaft_length", 0.25},
                                  {"shaft_diameter", 0.06},
                                  {"head_length", 0.15},
                                  {"head_diameter", 0.14},
                                  {"color", color(c)}}});
    else
      e["spheres"] = json::array({sphere(p.x, p.y, 0.05, 0.25, c)});
    e["texts"] = json::array({{{"pose", pose(p.x, p.y, 0.35)},
                               {"billboard", true},
                               {"font_size", 14.0},
                               {"scale_invariant", true},
                               {"color", color(c)},
                               {"text", id}}});
    entities.push_back(std::move(e));
  }
  return json{{"deletions", json::array()}, {"entities", std::move(entities)}}.dump();
}

std::string transforms_message(const FleetModel& fleet, int64_t stamp_ns) {
  json transforms = json::array();
  for (const auto& [id, r] : fleet.robots()) {
    if (!r.has_state) continue;
    const Pose& p = r.state.pose;
    transforms.push_back({{"timestamp", time_of(stamp_ns)},
                          {"parent_frame_id", kMapFrame},
                          {"child_frame_id", id},
                          {"translation", vec3(p.x, p.y, 0.0)},
                          {"rotation", yaw(p.theta)}});
  }
  return json{{"transforms", std::move(transforms)}}.dump();
}

std::string paths_message(const FleetModel& fleet, int64_t stamp_ns) {
  json entities = json::array();
  for (const auto& [id, r] : fleet.robots()) {
    if (!r.has_path) continue;
    json e = entity("path/" + id, stamp_ns);
    const RobotPathInput& path = r.path;
    if (path.status == PathStatus::Active) {
      Rgba c = robot_color(id);
      c.a = 0.8;
      json points = json::array();
      if (r.has_state) points.push_back(vec3(r.state.pose.x, r.state.pose.y, 0.02));
      for (size_t i = path.current; i < path.waypoints.size(); ++i)
        points.push_back(vec3(path.waypoints[i].x, path.waypoints[i].y, 0.02));
      if (points.size() >= 2)
        e["lines"] = json::array({{{"type", kLineStrip},
                                   {"pose", pose(0.0, 0.0, 0.0)},
                                   {"thickness", 0.04},
                                   {"scale_invariant", false},
                                   {"points", std::move(points)},
                                   {"color", color(c)},
                                   {"colors", json::array()},
                                   {"indices", json::array()}}});
      e["spheres"] = json::array({sphere(path.target.x, path.target.y, 0.02, 0.2, c)});
    }
    e["metadata"] = json::array({{{"key", "robot_id"}, {"value", id}},
                                 {{"key", "mode"}, {"value", path.mode}},
                                 {{"key", "status"}, {"value", status_name(path.status)}}});
    entities.push_back(std::move(e));
  }
  return json{{"deletions", json::array()}, {"entities", std::move(entities)}}.dump();
}

std::string points_message(const FleetModel& fleet, int64_t stamp_ns) {
  constexpr size_t kStride = 12;  // x, y, z as float32
  std::vector<uint8_t> bytes;
  size_t total = 0;
  for (const auto& [id, r] : fleet.robots()) total += r.points.size();
  bytes.resize(total * kStride);
  uint8_t* out = bytes.data();
  for (const auto& [id, r] : fleet.robots())
    r.points.for_each([&out](Vec2 p) {
      const float xyz[3] = {static_cast<float>(p.x), static_cast<float>(p.y), 0.0f};
      std::memcpy(out, xyz, kStride);  // little-endian hosts only, as the schema wants
      out += kStride;
    });
  const json message = {{"timestamp", time_of(stamp_ns)},
                        {"frame_id", kMapFrame},
                        {"pose", pose(0.0, 0.0, 0.0)},
                        {"point_stride", kStride},
                        {"fields", json::array({{{"name", "x"}, {"offset", 0}, {"type", kNumericFloat32}},
                                                {{"name", "y"}, {"offset", 4}, {"type", kNumericFloat32}},
                                                {{"name", "z"}, {"offset", 8}, {"type", kNumericFloat32}}})},
                        {"data", base64(bytes)}};
  return message.dump();
}

std::string health_message(const FleetModel& fleet, int64_t now_mono_ns, int64_t stamp_ns) {
  json services = json::array();
  for (const auto& [key, s] : fleet.services())
    services.push_back(
        {{"service", s.beat.service},
         {"instance_id", s.beat.instance_id},
         {"host", s.beat.host},
         {"pid", s.beat.pid},
         {"state", s.beat.state},
         {"uptime_s", s.beat.uptime_s},
         {"last_heard_s", static_cast<double>(std::max<int64_t>(now_mono_ns - s.heard_ns, 0)) / 1e9}});
  return json{{"timestamp", time_of(stamp_ns)}, {"services", std::move(services)}}.dump();
}

}  // namespace slam::bridge
