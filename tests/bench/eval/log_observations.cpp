// A robot log's scans as observations (log_observations.hpp).
#include "eval/log_observations.hpp"

#include <algorithm>
#include <cmath>

namespace slam::bench {

namespace {

constexpr size_t kV1MaxPoints = 16;  // a legacy robot's message: its position and up to 16 points

double to_centimetres(double m) {
  return std::round(m * 100.0) / 100.0;
}

}  // namespace

std::vector<size_t> thinned_beams(size_t total, int count) {
  std::vector<size_t> out;
  if (count <= 0 || static_cast<size_t>(count) >= total) {
    out.resize(total);
    for (size_t i = 0; i < total; ++i) out[i] = i;
    return out;
  }
  const double step = static_cast<double>(total) / count;
  for (int k = 0; k < count; ++k) out.push_back(static_cast<size_t>((k + 0.5) * step));
  return out;
}

LogObservations log_observations(std::span<const robot_log::LaserScan> scans,
                                 const LogObservationOptions& o) {
  LogObservations out;
  out.observations.reserve(scans.size());
  int64_t arrival = 0;
  std::vector<size_t> beams;
  for (size_t i = 0; i < scans.size(); ++i) {
    const robot_log::LaserScan& s = scans[i];
    const Pose sensor = s.odom.compose(s.laser_in_robot);
    out.stamps_s.push_back(s.stamp_s);
    out.sensor_odom.push_back(sensor);
    out.sensor_in_robot.push_back(s.laser_in_robot);
    arrival = std::max(arrival, static_cast<int64_t>(std::llround(s.stamp_s * 1e9)));

    mapper::OwnedObservation& obs = out.observations.emplace_back();
    obs.robot_id = o.robot;
    obs.seq = i + 1;
    obs.stamp_ns = arrival;
    obs.robot_stamp_ns = static_cast<int64_t>(std::llround(s.stamp_s * 1e9));
    obs.x = o.v1 ? to_centimetres(sensor.x) : sensor.x;
    obs.y = o.v1 ? to_centimetres(sensor.y) : sensor.y;
    obs.theta = o.v1 ? 0.0 : sensor.theta;
    obs.has_heading = !o.v1;
    beams = thinned_beams(s.ranges.size(), o.beams);
    for (size_t b : beams) {
      const double angle = sensor.theta + s.angle_min_rad + static_cast<double>(b) * s.angle_increment_rad;
      const bool hit = s.is_return(b) && s.ranges[b] <= o.max_range_m;
      const double range = hit ? s.ranges[b] : std::min(o.max_range_m, o.free_range_m);
      const Vec2 end{sensor.x + range * std::cos(angle), sensor.y + range * std::sin(angle)};
      if (o.v1) {
        if (hit && obs.hits.size() < kV1MaxPoints)
          obs.hits.push_back({to_centimetres(end.x), to_centimetres(end.y)});
      } else {
        (hit ? obs.hits : obs.misses).push_back(end);
      }
    }
  }
  return out;
}

}  // namespace slam::bench
