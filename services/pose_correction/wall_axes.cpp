#include "pose_correction/wall_axes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace slam::correction {

namespace {

constexpr double kQuarterTurn = std::numbers::pi / 2.0;
constexpr double kCoarseStep_rad = 2.0 * std::numbers::pi / 180.0;
constexpr double kFineStep_rad = 0.5 * std::numbers::pi / 180.0;
constexpr double kMaxOffLine = 0.2;  // share of a line's window that may lie off it

// A total least squares line fit: the line's direction is the principal axis of its points.
struct LineStats {
  Vec2 mean;
  double angle = 0.0;       // of the line
  double along_sum = 0.0;   // sum of the squared offsets of the points from the mean along it
  double across_sum = 0.0;  // ...and across it
  double length = 0.0;      // between the outermost points along it
  size_t points = 0;

  double offset(Vec2 q) const { return -(q.x - mean.x) * std::sin(angle) + (q.y - mean.y) * std::cos(angle); }
  double spread_across() const {
    return std::sqrt(across_sum / std::max(1.0, static_cast<double>(points) - 2.0));
  }
};

LineStats fit_line(std::span<const Vec2> points) {
  LineStats line;
  line.points = points.size();
  const auto n = static_cast<double>(points.size());
  for (const Vec2& q : points) line.mean = {line.mean.x + q.x / n, line.mean.y + q.y / n};
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const Vec2& q : points) {
    const double dx = q.x - line.mean.x, dy = q.y - line.mean.y;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  line.angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  const double spread = std::hypot(0.5 * (sxx - syy), sxy);
  line.along_sum = 0.5 * (sxx + syy) + spread;
  line.across_sum = std::max(0.0, 0.5 * (sxx + syy) - spread);
  double lo = 0.0, hi = 0.0;
  for (const Vec2& q : points) {
    const double t = (q.x - line.mean.x) * std::cos(line.angle) + (q.y - line.mean.y) * std::sin(line.angle);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  line.length = hi - lo;
  return line;
}

}  // namespace

double wrap_quarter(double angle) {
  return angle - kQuarterTurn * std::floor((angle + kQuarterTurn / 2.0) / kQuarterTurn);
}

// Walls along `direction` (projection 0) and across it (projection 1) put their points at one
// offset along the projection's normal.
Vec2 WallAxisReader::normal(int projection, double direction) {
  return projection == 0 ? Vec2{-std::sin(direction), std::cos(direction)}
                         : Vec2{std::cos(direction), std::sin(direction)};
}

size_t WallAxisReader::band(int projection, double offset) const {
  const auto index =
      static_cast<int64_t>(std::floor(offset / options_.line_band_m)) + static_cast<int64_t>(per_side_);
  return static_cast<size_t>(projection) * 2 * per_side_ + static_cast<size_t>(index);
}

// The sum of the squared counts per band is largest when the bands run along the walls.
double WallAxisReader::concentration(std::span<const Vec2> points, Vec2 centre, double direction) {
  std::fill(bins_.begin(), bins_.end(), 0);
  for (int projection = 0; projection < 2; ++projection) {
    const Vec2 n = normal(projection, direction);
    for (const Vec2& p : points) ++bins_[band(projection, (p.x - centre.x) * n.x + (p.y - centre.y) * n.y)];
  }
  double sum = 0.0;
  for (int32_t count : bins_) sum += static_cast<double>(count) * count;
  return sum;
}

void WallAxisReader::collect_lines(std::span<const Vec2> points, Vec2 centre, double direction) {
  lines_.clear();
  const size_t half = bins_.size() / 2;
  (void)concentration(points, centre, direction);
  for (int projection = 0; projection < 2; ++projection) {
    const Vec2 across = normal(projection, direction);
    const size_t first = static_cast<size_t>(projection) * half;
    for (size_t b = first + 2; b + 2 < first + half; ++b) {
      // A band holding more than any other within two (ties go to the lower one) seeds a line of
      // the points within two bands of it: wide enough that a noisy wall shows its whole spread
      // (and is refused) rather than the part a narrow window would cut out.
      const int32_t count = bins_[b] + bins_[b - 1] + bins_[b + 1];
      if (bins_[b] == 0 || bins_[b] < bins_[b - 1] || bins_[b] < bins_[b - 2] || bins_[b] <= bins_[b + 1] ||
          bins_[b] <= bins_[b + 2] || count < options_.min_line_points) {
        continue;
      }
      const double low =
          (static_cast<double>(b - first) - static_cast<double>(per_side_) - 2.0) * options_.line_band_m;
      const double high = low + 5.0 * options_.line_band_m;
      line_points_.clear();
      for (const Vec2& p : points) {
        const Vec2 d{p.x - centre.x, p.y - centre.y};
        const double offset = d.x * across.x + d.y * across.y;
        if (offset >= low && offset < high) line_points_.push_back(d);
      }
      if (line_points_.size() < static_cast<size_t>(options_.min_line_points)) continue;
      // Refit without the few points far off the line (the end of a wall meeting it at a corner);
      // a wall with many such points is too noisy to read a direction from.
      const LineStats window = fit_line(line_points_);
      const size_t before = line_points_.size();
      std::erase_if(line_points_,
                    [&](const Vec2& q) { return std::abs(window.offset(q)) > 3.0 * options_.point_sigma_m; });
      if (line_points_.size() < static_cast<size_t>(options_.min_line_points) ||
          static_cast<double>(line_points_.size()) < (1.0 - kMaxOffLine) * static_cast<double>(before)) {
        continue;
      }
      const LineStats line = fit_line(line_points_);
      const double spread = line.spread_across();
      if (spread > options_.max_line_spread_m) continue;
      const double sigma_across = std::max(options_.point_sigma_m, spread);
      const double tilt = wrap_quarter(line.angle - direction);
      if (line.length < options_.min_line_length_m || std::abs(tilt) > options_.max_line_tilt_rad) continue;
      // The direction of a fitted line is known to sigma_across over the root of the points'
      // summed squared spread along it.
      lines_.push_back(LineFit{direction + tilt, line.along_sum / (sigma_across * sigma_across),
                               static_cast<int>(line_points_.size())});
    }
  }
}

// A robot standing still hits the same few spots again and again: as many points, two such spots
// would make a "line" of great weight in any direction between them. One point per cell (the mean
// of its hits) counts each place on a wall once.
void WallAxisReader::thin(std::span<const Vec2> points) {
  const double cell = options_.thinning_cell_m;
  keyed_.clear();
  for (const Vec2& p : points) {
    if (!(std::isfinite(p.x) && std::isfinite(p.y))) continue;
    keyed_.push_back(
        {static_cast<int64_t>(std::floor(p.x / cell)), static_cast<int64_t>(std::floor(p.y / cell)), p});
  }
  std::sort(keyed_.begin(), keyed_.end(),
            [](const Keyed& a, const Keyed& b) { return a.cx != b.cx ? a.cx < b.cx : a.cy < b.cy; });
  thinned_.clear();
  for (size_t i = 0; i < keyed_.size();) {
    size_t j = i;
    Vec2 sum{0.0, 0.0};
    for (; j < keyed_.size() && keyed_[j].cx == keyed_[i].cx && keyed_[j].cy == keyed_[i].cy; ++j) {
      sum = {sum.x + keyed_[j].point.x, sum.y + keyed_[j].point.y};
    }
    const auto count = static_cast<double>(j - i);
    thinned_.push_back({sum.x / count, sum.y / count});
    i = j;
  }
}

std::optional<WallAxisReading> WallAxisReader::read(std::span<const Vec2> raw_points,
                                                    const WallAxisOptions& options) {
  options_ = options;
  thin(raw_points);
  const std::span<const Vec2> points = thinned_;
  if (points.size() < static_cast<size_t>(options_.min_line_points)) return std::nullopt;
  Vec2 centre{0.0, 0.0};
  const auto n = static_cast<double>(points.size());
  for (const Vec2& p : points) centre = {centre.x + p.x / n, centre.y + p.y / n};
  double reach = 0.0;
  for (const Vec2& p : points) reach = std::max(reach, distance(p, centre));
  if (!std::isfinite(reach)) return std::nullopt;
  per_side_ = static_cast<size_t>(std::ceil(reach / options_.line_band_m)) + 2;
  bins_.assign(2 * 2 * per_side_, 0);  // two projections of 2 * per_side_ bands each

  // Coarse search over a quarter turn, then a finer one around the best.
  double best = 0.0, best_score = -1.0;
  for (double a = -kQuarterTurn / 2.0; a < kQuarterTurn / 2.0; a += kCoarseStep_rad) {
    const double score = concentration(points, centre, a);
    if (score > best_score) {
      best_score = score;
      best = a;
    }
  }
  const double coarse = best;
  for (double a = coarse - kCoarseStep_rad; a <= coarse + kCoarseStep_rad + 1e-9; a += kFineStep_rad) {
    const double score = concentration(points, centre, a);
    if (score > best_score) {
      best_score = score;
      best = a;
    }
  }

  collect_lines(points, centre, best);
  if (lines_.empty()) return std::nullopt;
  double weight = 0.0, weighted_tilt = 0.0;
  int on_lines = 0;
  for (const LineFit& line : lines_) {
    weight += line.weight;
    weighted_tilt += line.weight * wrap_quarter(line.angle - best);
    on_lines += line.points;
  }
  WallAxisReading reading;
  reading.angle = wrap_quarter(best + weighted_tilt / weight);
  reading.sigma = 1.0 / std::sqrt(weight);
  reading.lines = static_cast<int>(lines_.size());
  reading.points = on_lines;
  if (!(reading.sigma <= options_.max_sigma_rad)) return std::nullopt;
  return reading;
}

void QuarterTurnMean::add(double angle, double weight) {
  if (!(std::isfinite(angle) && std::isfinite(weight) && weight > 0.0)) return;
  sum_cos_ += weight * std::cos(4.0 * angle);
  sum_sin_ += weight * std::sin(4.0 * angle);
  sum_weights_ += weight;
  ++count_;
}

double QuarterTurnMean::mean() const {
  return wrap_quarter(std::atan2(sum_sin_, sum_cos_) / 4.0);
}

double QuarterTurnMean::agreement() const {
  return sum_weights_ > 0.0 ? std::hypot(sum_cos_, sum_sin_) / sum_weights_ : 0.0;
}

void MapWallAxes::anchor(double axis_in_map, double weight) {
  if (!(std::isfinite(axis_in_map) && std::isfinite(weight) && weight > 0.0)) return;
  anchors_.push_back({axis_in_map, weight});
  anchor_mean_.add(axis_in_map, weight);
  // The weighted median, each anchor taken modulo a quarter turn nearest the mean. Anchors come
  // a few per robot start, so this runs rarely; axis() reads the result.
  const double mean = anchor_mean_.mean();
  for (Anchor& a : anchors_) a.angle = mean + wrap_quarter(a.angle - mean);
  std::sort(anchors_.begin(), anchors_.end(),
            [](const Anchor& a, const Anchor& b) { return a.angle < b.angle; });
  double total = 0.0;
  for (const Anchor& a : anchors_) total += a.weight;
  double below = 0.0;
  for (const Anchor& a : anchors_) {
    below += a.weight;
    if (below >= 0.5 * total) {
      anchor_median_ = wrap_quarter(a.angle);
      break;
    }
  }
}

void MapWallAxes::learn(double axis_in_map) {
  readings_.add(axis_in_map, 1.0);
}

std::optional<double> MapWallAxes::axis() const {
  if (anchors_.empty() || readings_.count() < kMinReadings) return std::nullopt;
  if (anchor_mean_.agreement() < kMinAgreement || readings_.agreement() < kMinAgreement) return std::nullopt;
  return anchor_median_;
}

double heading_correction(double map_axis, const WallAxisReading& reading, double heading) {
  return wrap_quarter(map_axis - (reading.angle + heading));
}

}  // namespace slam::correction
