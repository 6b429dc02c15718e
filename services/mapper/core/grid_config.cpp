// Validation of GridConfig: every rule names its key so a bad request can be answered precisely.
#include "mapper/core/grid_config.hpp"

#include <cmath>
#include <string>

namespace slam::mapper {
namespace {

Error bad(const char* key, const std::string& why) {
  return Error{std::string(key) + ": " + why};
}

std::string num(double v) {
  std::string s = std::to_string(v);
  while (s.size() > 1 && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

bool positive(double v) {
  return std::isfinite(v) && v > 0.0;
}

}  // namespace

int64_t cells_for(double metres, double resolution) {
  const double cells = std::ceil(metres / resolution - 1e-9);
  if (!(cells < 1e15)) return INT64_MAX;
  return cells < 1.0 ? 1 : static_cast<int64_t>(cells);
}

Status validate(const GridConfig& c) {
  if (!positive(c.resolution) || c.resolution < 1e-3)
    return bad("resolution", "must be a finite number >= 0.001 m, got " + num(c.resolution));
  if (!std::isfinite(c.origin_x) || std::abs(c.origin_x) > 1e6)
    return bad("origin_x", "must be finite, |x| <= 1e6");
  if (!std::isfinite(c.origin_y) || std::abs(c.origin_y) > 1e6)
    return bad("origin_y", "must be finite, |y| <= 1e6");
  if (!positive(c.width_m)) return bad("width_m", "must be > 0, got " + num(c.width_m));
  if (!positive(c.height_m)) return bad("height_m", "must be > 0, got " + num(c.height_m));
  if (!positive(c.max_extent_m)) return bad("max_extent_m", "must be > 0, got " + num(c.max_extent_m));
  if (c.width_m > c.max_extent_m || c.height_m > c.max_extent_m)
    return bad("max_extent_m", "must be at least width_m and height_m (" + num(c.max_extent_m) + " m)");
  const int64_t side = cells_for(c.max_extent_m, c.resolution);
  if (side > kMaxCellsPerSide || side * side > kMaxCells)
    return bad("max_extent_m",
               num(c.max_extent_m) + " m at " + num(c.resolution) + " m/cell needs " + std::to_string(side) +
                   " cells per side, more than the limit of " +
                   std::to_string(static_cast<int64_t>(std::sqrt(static_cast<double>(kMaxCells)))));
  if (!positive(c.grow_chunk_m)) return bad("grow_chunk_m", "must be > 0, got " + num(c.grow_chunk_m));
  if (!positive(c.max_range_m)) return bad("max_range_m", "must be > 0, got " + num(c.max_range_m));
  if (!std::isfinite(c.inflation_radius) || c.inflation_radius < 0.0)
    return bad("inflation_radius", "must be finite and >= 0, got " + num(c.inflation_radius));
  if (c.inflation_radius / c.resolution > kMaxInflationCells)
    return bad("inflation_radius", "must be at most " + std::to_string(kMaxInflationCells) + " cells");
  const LogOddsConfig& l = c.log_odds;
  if (l.hit <= 0) return bad("log_odds.hit", "must be > 0");
  if (l.miss >= 0) return bad("log_odds.miss", "must be < 0");
  if (!(l.clamp_min <= l.free_threshold && l.free_threshold < 0))
    return bad("log_odds.free_threshold", "must satisfy clamp_min <= free_threshold < 0");
  if (!(0 < l.occupied_threshold && l.occupied_threshold <= l.clamp_max))
    return bad("log_odds.occupied_threshold", "must satisfy 0 < occupied_threshold <= clamp_max");
  if (l.prior_occupied < l.occupied_threshold || l.prior_occupied > l.clamp_max)
    return bad("log_odds.prior_occupied", "must be within [occupied_threshold, clamp_max]");
  if (l.prior_free > l.free_threshold || l.prior_free < l.clamp_min)
    return bad("log_odds.prior_free", "must be within [clamp_min, free_threshold]");
  return Status::ok();
}

}  // namespace slam::mapper
