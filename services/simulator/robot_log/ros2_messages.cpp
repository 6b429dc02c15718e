// ROS 2 message decoding (ros2_messages.hpp). Field order follows the .msg definitions; fields after
// the last one used (covariances, twist, intensities) are not read.
#include "simulator/robot_log/ros2_messages.hpp"

#include <cmath>

#include "simulator/robot_log/cdr_reader.hpp"

namespace slam::robot_log {

namespace {

// std_msgs/msg/Header: builtin_interfaces/msg/Time stamp (int32 sec, uint32 nanosec), string frame_id.
bool header(CdrReader& r, Ros2Header& h) {
  int32_t sec = 0;
  uint32_t nanosec = 0;
  if (!r.i32(sec) || !r.u32(nanosec) || !r.string(h.frame_id)) return false;
  h.stamp_s = sec + nanosec * 1e-9;
  return true;
}

bool vec3(CdrReader& r, Vec3d& v) {
  return r.f64(v.x) && r.f64(v.y) && r.f64(v.z);
}

bool quaternion(CdrReader& r, Quaternion& q) {
  return r.f64(q.x) && r.f64(q.y) && r.f64(q.z) && r.f64(q.w);
}

bool finite(const Vec3d& v, const Quaternion& q) {
  return std::isfinite(v.x + v.y + v.z + q.x + q.y + q.z + q.w) &&
         q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w > 0;
}

}  // namespace

Result<Ros2LaserScan> decode_laser_scan(std::span<const uint8_t> cdr) {
  auto r = CdrReader::open(cdr);
  if (!r) return r.error();
  Ros2LaserScan s;
  float time_increment = 0, scan_time = 0;
  if (!header(*r, s.header) || !r->f32(s.angle_min) || !r->f32(s.angle_max) || !r->f32(s.angle_increment) ||
      !r->f32(time_increment) || !r->f32(scan_time) || !r->f32(s.range_min) || !r->f32(s.range_max) ||
      !r->f32_sequence(s.ranges))
    return Error{"LaserScan runs past its end"};
  if (!std::isfinite(s.header.stamp_s + s.angle_min + s.angle_increment + s.range_min + s.range_max))
    return Error{"LaserScan with a non-finite angle or range limit"};
  if (!(s.range_max > 0)) return Error{"LaserScan with range_max <= 0"};
  return s;
}

Result<Ros2Odometry> decode_odometry(std::span<const uint8_t> cdr) {
  auto r = CdrReader::open(cdr);
  if (!r) return r.error();
  Ros2Odometry o;
  if (!header(*r, o.header) || !r->string(o.child_frame_id) || !vec3(*r, o.position) ||
      !quaternion(*r, o.orientation))
    return Error{"Odometry runs past its end"};
  if (!finite(o.position, o.orientation)) return Error{"Odometry with a non-finite or zero pose"};
  return o;
}

Result<std::vector<Ros2Transform>> decode_tf_message(std::span<const uint8_t> cdr) {
  auto r = CdrReader::open(cdr);
  if (!r) return r.error();
  uint32_t n = 0;
  if (!r->u32(n)) return Error{"TFMessage runs past its end"};
  std::vector<Ros2Transform> out;
  for (uint32_t i = 0; i < n; ++i) {  // each transform takes bytes, so a forged count ends soon
    Ros2Transform t;
    if (!header(*r, t.header) || !r->string(t.child_frame_id) || !vec3(*r, t.translation) ||
        !quaternion(*r, t.rotation))
      return Error{"TFMessage runs past its end"};
    if (!finite(t.translation, t.rotation)) return Error{"TFMessage with a non-finite or zero transform"};
    out.push_back(std::move(t));
  }
  return out;
}

}  // namespace slam::robot_log
