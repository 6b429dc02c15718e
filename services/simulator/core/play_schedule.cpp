// The log player's schedule (play_schedule.hpp).
#include "simulator/core/play_schedule.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace slam::sim {

Result<std::vector<PlayPiece>> plan_pieces(const robot_log::RobotLog& log, size_t log_index,
                                           const std::string& robot_id, const PlayOptions& options) {
  const auto& scans = log.scans;
  if (scans.empty()) return Error{"the log holds no scans"};
  const double t0 = scans.front().stamp_s;
  const auto offset = [&](size_t i) { return scans[i].stamp_s - t0; };
  size_t first = 0;
  while (first < scans.size() && offset(first) < options.start_s) ++first;
  size_t end = scans.size();
  if (options.end_s > 0)
    while (end > first && offset(end - 1) > options.end_s) --end;
  const size_t count = end - first;
  const auto pieces = static_cast<size_t>(std::max(options.pieces, 1));
  if (count < pieces)
    return Error{fmt::format("{} scans between {} s and {} s of the log, fewer than {} pieces", count,
                             options.start_s, options.end_s > 0 ? options.end_s : offset(scans.size() - 1),
                             pieces)};
  std::vector<PlayPiece> out;
  for (size_t k = 0; k < pieces; ++k) {
    PlayPiece p;
    p.robot_id = pieces == 1 ? robot_id : fmt::format("{}-{}", robot_id, k + 1);
    p.log = log_index;
    p.first = first + count * k / pieces;
    p.end = first + count * (k + 1) / pieces;
    out.push_back(std::move(p));
  }
  return out;
}

std::vector<double> send_times(const robot_log::RobotLog& log, const PlayPiece& piece, double rate) {
  std::vector<double> out(piece.size());
  if (out.empty()) return out;
  double t0 = log.scans[piece.first].stamp_s;  // the stamp sent at `base`
  double base = 0;
  double last = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    const double stamp = log.scans[piece.first + i].stamp_s;
    if (i > 0 && std::abs(stamp - log.scans[piece.first + i - 1].stamp_s) > robot_log::kStampJumpS) {
      t0 = stamp;
      base = last;
    }
    const double t = rate > 0 ? base + (stamp - t0) / rate : kFastPaceS * static_cast<double>(i);
    last = std::max(last, t);
    out[i] = last;
  }
  return out;
}

PlayedScan prepare_scan(const robot_log::LaserScan& scan, int beams, double clip_m) {
  PlayedScan out;
  out.stamp_s = scan.stamp_s;
  out.odom = scan.odom;
  out.sensor = scan.laser_in_robot;
  out.max_range = clip_m > 0 ? std::min(scan.max_range_m, clip_m) : scan.max_range_m;
  const size_t n = scan.ranges.size();
  const size_t kept = beams > 0 ? std::min(n, static_cast<size_t>(beams)) : n;
  out.angles.reserve(kept);
  out.ranges.reserve(kept);
  for (size_t k = 0; k < kept; ++k) {
    // The centre of sector k of `kept` equal sectors; every beam when kept == n.
    const auto i = static_cast<size_t>((static_cast<double>(k) + 0.5) * static_cast<double>(n) /
                                       static_cast<double>(kept));
    const double r = scan.ranges[std::min(i, n - 1)];
    if (!(r > 0)) continue;  // an error reading (0, negative, NaN): unknown, not free space
    out.angles.push_back(scan.angle_min_rad +
                         scan.angle_increment_rad * static_cast<double>(std::min(i, n - 1)));
    out.ranges.push_back(r < out.max_range ? r : out.max_range);
  }
  return out;
}

}  // namespace slam::sim
