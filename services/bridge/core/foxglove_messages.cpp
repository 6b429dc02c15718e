// Foxglove JSON messages from the fleet model (see foxglove_messages.hpp).
#include "bridge/core/foxglove_messages.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "bridge/core/json_writer.hpp"
#include "common/core/cell_class.hpp"

namespace slam::bridge {
namespace {

void write_time(JsonWriter& w, std::string_view key, int64_t stamp_ns) {
  const int64_t ns = std::max<int64_t>(stamp_ns, 0);
  w.key(key)
      .begin_object()
      .key("sec")
      .value(ns / 1'000'000'000)
      .key("nsec")
      .value(ns % 1'000'000'000)
      .end_object();
}

void write_vec3(JsonWriter& w, std::string_view key, double x, double y, double z) {
  w.key(key).begin_object().key("x").value(x).key("y").value(y).key("z").value(z).end_object();
}

// Rotation about +z by `theta`.
void write_yaw(JsonWriter& w, std::string_view key, double theta) {
  w.key(key).begin_object().key("x").value(0.0).key("y").value(0.0);
  w.key("z").value(std::sin(theta / 2.0)).key("w").value(std::cos(theta / 2.0)).end_object();
}

void write_pose(JsonWriter& w, double x, double y, double z, double theta = 0.0) {
  w.key("pose").begin_object();
  write_vec3(w, "position", x, y, z);
  write_yaw(w, "orientation", theta);
  w.end_object();
}

void write_color(JsonWriter& w, const Rgba& c) {
  w.key("color").begin_object().key("r").value(c.r).key("g").value(c.g).key("b").value(c.b);
  w.key("a").value(c.a).end_object();
}

// Opens a SceneEntity in the map frame; the caller writes metadata and the primitive lists it has,
// then close_entity() adds the remaining lists empty, as the schema requires all of them.
class EntityWriter {
 public:
  EntityWriter(JsonWriter& w, std::string_view id, int64_t stamp_ns) : w_(w) {
    w.begin_object();
    write_time(w, "timestamp", stamp_ns);
    w.key("frame_id").value(kMapFrame).key("id").value(id);
    w.key("lifetime").begin_object().key("sec").value(0).key("nsec").value(0).end_object();
    w.key("frame_locked").value(false);
  }
  // Starts the list `name` (one of kLists); the caller fills it and ends it.
  JsonWriter& list(std::string_view name) {
    for (size_t i = 0; i < kLists.size(); ++i)
      if (kLists[i] == name) written_[i] = true;
    return w_.key(name).begin_array();
  }
  void close() {
    for (size_t i = 0; i < kLists.size(); ++i)
      if (!written_[i]) w_.empty_array(kLists[i]);
    w_.end_object();
  }

 private:
  static constexpr std::array<std::string_view, 9> kLists = {
      "metadata", "arrows", "cubes", "spheres", "cylinders", "lines", "triangles", "texts", "models"};
  JsonWriter& w_;
  std::array<bool, 9> written_{};
};

void write_sphere(JsonWriter& w, double x, double y, double z, double size, const Rgba& c) {
  w.begin_object();
  write_pose(w, x, y, z);
  write_vec3(w, "size", size, size, size);
  write_color(w, c);
  w.end_object();
}

void write_numeric_field(JsonWriter& w, std::string_view name, int offset, uint8_t type) {
  w.begin_object()
      .key("name")
      .value(name)
      .key("offset")
      .value(offset)
      .key("type")
      .value(int{type})
      .end_object();
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
  std::string out;
  out.reserve(bytes.size() * 4 / 3 + 512);
  JsonWriter w(out);
  w.begin_object();
  write_time(w, "timestamp", stamp_ns);
  w.key("frame_id").value(kMapFrame);
  write_pose(w, corner.x, corner.y, 0.0);
  w.key("column_count").value(box.width);
  w.key("cell_size")
      .begin_object()
      .key("x")
      .value(geometry.resolution)
      .key("y")
      .value(geometry.resolution)
      .end_object();
  w.key("row_stride").value(box.width).key("cell_stride").value(1);
  w.key("fields").begin_array();
  write_numeric_field(w, "occupancy", 0, kNumericInt8);
  w.end_array();
  w.key("data").base64_value(bytes);
  w.end_object();
  return out;
}

std::string robots_message(const FleetModel& fleet, int64_t stamp_ns) {
  std::string out;
  JsonWriter w(out);
  w.begin_object().empty_array("deletions").key("entities").begin_array();
  for (const auto& [id, r] : fleet.robots()) {
    if (!r.has_state) continue;
    Rgba c = robot_color(id);
    if (!r.state.online) c.a = 0.35;
    const Pose& p = r.state.pose;
    EntityWriter e(w, "robot/" + id, stamp_ns);
    e.list("metadata");
    for (const auto& [k, v] : {std::pair<const char*, std::string_view>{"robot_id", id},
                               {"online", r.state.online ? "true" : "false"}})
      w.begin_object().key("key").value(k).key("value").value(v).end_object();
    w.end_array();
    if (r.state.has_heading) {
      e.list("arrows").begin_object();
      write_pose(w, p.x, p.y, 0.05, p.theta);
      w.key("shaft_length").value(0.25).key("shaft_diameter").value(0.06);
      w.key("head_length").value(0.15).key("head_diameter").value(0.14);
      write_color(w, c);
      w.end_object().end_array();
    } else {
      e.list("spheres");
      write_sphere(w, p.x, p.y, 0.05, 0.25, c);
      w.end_array();
    }
    e.list("texts").begin_object();
    write_pose(w, p.x, p.y, 0.35);
    w.key("billboard").value(true).key("font_size").value(14.0).key("scale_invariant").value(true);
    write_color(w, c);
    w.key("text").value(id).end_object().end_array();
    e.close();
  }
  w.end_array().end_object();
  return out;
}

std::string transforms_message(const FleetModel& fleet, int64_t stamp_ns) {
  std::string out;
  JsonWriter w(out);
  w.begin_object().key("transforms").begin_array();
  for (const auto& [id, r] : fleet.robots()) {
    if (!r.has_state) continue;
    const Pose& p = r.state.pose;
    w.begin_object();
    write_time(w, "timestamp", stamp_ns);
    w.key("parent_frame_id").value(kMapFrame).key("child_frame_id").value(id);
    write_vec3(w, "translation", p.x, p.y, 0.0);
    write_yaw(w, "rotation", p.theta);
    w.end_object();
  }
  w.end_array().end_object();
  return out;
}

std::string paths_message(const FleetModel& fleet, int64_t stamp_ns) {
  std::string out;
  JsonWriter w(out);
  w.begin_object().empty_array("deletions").key("entities").begin_array();
  for (const auto& [id, r] : fleet.robots()) {
    if (!r.has_path) continue;
    const msg::RobotPath& path = r.path;
    EntityWriter e(w, "path/" + id, stamp_ns);
    e.list("metadata");
    for (const auto& [k, v] : {std::pair<const char*, std::string_view>{"robot_id", id},
                               {"mode", msg::goal_mode_name(path.mode)},
                               {"status", msg::goal_status_name(path.status)}})
      w.begin_object().key("key").value(k).key("value").value(v).end_object();
    w.end_array();
    if (path.status == msg::GoalStatus::Active) {
      Rgba c = robot_color(id);
      c.a = 0.8;
      const size_t remaining = path.waypoints.size() - std::min<size_t>(path.current, path.waypoints.size());
      if (remaining + (r.has_state ? 1 : 0) >= 2) {
        e.list("lines").begin_object().key("type").value(int{kLineStrip});
        write_pose(w, 0.0, 0.0, 0.0);
        w.key("thickness").value(0.04).key("scale_invariant").value(false);
        w.key("points").begin_array();
        if (r.has_state)
          w.begin_object()
              .key("x")
              .value(r.state.pose.x)
              .key("y")
              .value(r.state.pose.y)
              .key("z")
              .value(0.02)
              .end_object();
        for (size_t i = path.current; i < path.waypoints.size(); ++i)
          w.begin_object()
              .key("x")
              .value(path.waypoints[i].x)
              .key("y")
              .value(path.waypoints[i].y)
              .key("z")
              .value(0.02)
              .end_object();
        w.end_array();
        write_color(w, c);
        w.empty_array("colors").empty_array("indices").end_object().end_array();
      }
      e.list("spheres");
      write_sphere(w, path.target.x, path.target.y, 0.02, 0.2, c);
      w.end_array();
    }
    e.close();
  }
  w.end_array().end_object();
  return out;
}

std::string points_message(const FleetModel& fleet, int64_t stamp_ns) {
  constexpr size_t kStride = 12;  // x, y, z as float32
  std::vector<uint8_t> bytes;
  size_t total = 0;
  for (const auto& [id, r] : fleet.robots()) total += r.points.size();
  bytes.resize(total * kStride);
  uint8_t* out_bytes = bytes.data();
  for (const auto& [id, r] : fleet.robots())
    r.points.for_each([&out_bytes](Vec2 p) {
      const float xyz[3] = {static_cast<float>(p.x), static_cast<float>(p.y), 0.0f};
      std::memcpy(out_bytes, xyz, kStride);  // little-endian hosts only, as the schema wants
      out_bytes += kStride;
    });
  std::string out;
  out.reserve(bytes.size() * 4 / 3 + 512);
  JsonWriter w(out);
  w.begin_object();
  write_time(w, "timestamp", stamp_ns);
  w.key("frame_id").value(kMapFrame);
  write_pose(w, 0.0, 0.0, 0.0);
  w.key("point_stride").value(static_cast<int64_t>(kStride));
  w.key("fields").begin_array();
  write_numeric_field(w, "x", 0, kNumericFloat32);
  write_numeric_field(w, "y", 4, kNumericFloat32);
  write_numeric_field(w, "z", 8, kNumericFloat32);
  w.end_array();
  w.key("data").base64_value(bytes);
  w.end_object();
  return out;
}

std::string health_message(const FleetModel& fleet, int64_t now_mono_ns, int64_t stamp_ns) {
  std::string out;
  JsonWriter w(out);
  w.begin_object();
  write_time(w, "timestamp", stamp_ns);
  w.key("services").begin_array();
  for (const auto& [key, s] : fleet.services()) {
    w.begin_object().key("service").value(s.beat.service).key("instance_id").value(s.beat.instance_id);
    w.key("host")
        .value(s.beat.host)
        .key("pid")
        .value(s.beat.pid)
        .key("state")
        .value(msg::service_state_name(s.beat.state));
    w.key("uptime_s").value(s.beat.uptime_s);
    w.key("last_heard_s").value(static_cast<double>(std::max<int64_t>(now_mono_ns - s.heard_ns, 0)) / 1e9);
    w.end_object();
  }
  w.end_array().end_object();
  return out;
}

std::string alerts_message(const FleetModel& fleet, int64_t stamp_ns) {
  std::string out;
  JsonWriter w(out);
  w.begin_object();
  write_time(w, "timestamp", stamp_ns);
  w.key("alerts").begin_array();
  for (const auto& [id, a] : fleet.alerts()) {
    w.begin_object()
        .key("alert_id")
        .value(a.alert_id)
        .key("kind")
        .value(alerts::kind_id(a.kind))
        .key("subject")
        .value(a.subject);
    w.key("active").value(a.active);
    write_time(w, "raised", a.raised_ns);
    write_time(w, "changed", a.stamp_ns);
    w.key("message").value(a.message).key("raised_by").value(a.raised_by);
    w.end_object();
  }
  w.end_array().end_object();
  return out;
}

}  // namespace slam::bridge
