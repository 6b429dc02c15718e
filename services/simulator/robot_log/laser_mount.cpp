// Static transform chains (laser_mount.hpp).
#include "simulator/robot_log/laser_mount.hpp"

#include <cmath>
#include <string_view>

namespace slam::robot_log {

namespace {

std::string frame_name(std::string_view name) {
  if (!name.empty() && name.front() == '/') name.remove_prefix(1);
  return std::string(name);
}

Quaternion normalised(const Quaternion& q) {
  const double n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  return {q.x / n, q.y / n, q.z / n, q.w / n};
}

Quaternion multiply(const Quaternion& a, const Quaternion& b) {
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

Vec3d rotate(const Quaternion& q, const Vec3d& v) {
  // v + 2w (u x v) + 2 u x (u x v), u = (x, y, z)
  const Vec3d u{q.x, q.y, q.z};
  const Vec3d t{2 * (u.y * v.z - u.z * v.y), 2 * (u.z * v.x - u.x * v.z), 2 * (u.x * v.y - u.y * v.x)};
  return {v.x + q.w * t.x + (u.y * t.z - u.z * t.y), v.y + q.w * t.y + (u.z * t.x - u.x * t.z),
          v.z + q.w * t.z + (u.x * t.y - u.y * t.x)};
}

}  // namespace

void StaticFrames::add(const Ros2Transform& t) {
  parent_of_[frame_name(t.child_frame_id)] = {frame_name(t.header.frame_id), t.translation,
                                              normalised(t.rotation)};
}

std::optional<LaserMount> StaticFrames::mount(const std::string& base_frame,
                                              const std::string& laser_frame) const {
  const std::string base = frame_name(base_frame);
  std::string frame = frame_name(laser_frame);
  // base <- laser as translation + rotation, built from the laser end upwards.
  Vec3d translation;
  Quaternion rotation;
  for (int hops = 0; frame != base; ++hops) {
    const auto it = parent_of_.find(frame);
    if (it == parent_of_.end() || hops > 32) return std::nullopt;  // unlinked, or a loop
    const Link& link = it->second;
    const Vec3d moved = rotate(link.rotation, translation);
    translation = {link.translation.x + moved.x, link.translation.y + moved.y, link.translation.z + moved.z};
    rotation = multiply(link.rotation, rotation);
    frame = link.parent;
  }
  // The laser's x axis seen from the base gives its heading; its z axis, whether it looks down.
  const Vec3d x_axis = rotate(rotation, {1, 0, 0});
  const Vec3d z_axis = rotate(rotation, {0, 0, 1});
  return LaserMount{{translation.x, translation.y, std::atan2(x_axis.y, x_axis.x)}, z_axis.z < 0};
}

}  // namespace slam::robot_log
