#include "pose_correction/correlative_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slam::correction {

SearchLattice SearchLattice::around(const SearchWindow& window, double resolution, double max_range,
                                    double linear_step_m, double angular_step_rad) {
  SearchLattice l;
  l.step_cells = linear_step_m > 0.0
                     ? std::max<int32_t>(1, static_cast<int32_t>(std::lround(linear_step_m / resolution)))
                     : 1;
  l.step_m = l.step_cells * resolution;
  l.linear_steps = static_cast<int32_t>(std::ceil(window.linear_m / l.step_m - 1e-9));
  const double nominal_angular_step =
      angular_step_rad > 0.0 ? angular_step_rad : resolution / std::max(max_range, resolution);
  l.angular_steps = static_cast<int32_t>(std::ceil(window.angular_rad / nominal_angular_step - 1e-9));
  l.angular_step = l.angular_steps > 0 ? window.angular_rad / l.angular_steps : 0.0;
  return l;
}

Eigen::Vector3d SearchLattice::offset(size_t index) const {
  const auto h = static_cast<int32_t>(index / per_heading());
  const auto iy = static_cast<int32_t>(index % per_heading()) / side();
  const auto ix = static_cast<int32_t>(index % per_heading()) % side();
  return {(ix - linear_steps) * step_m, (iy - linear_steps) * step_m, (h - angular_steps) * angular_step};
}

bool SearchLattice::on_edge(const Eigen::Vector3d& o) const {
  const auto edge = [](double value, int32_t steps, double step) {
    return steps > 0 && std::abs(value) >= (steps - 0.5) * step;
  };
  return edge(o.x(), linear_steps, step_m) || edge(o.y(), linear_steps, step_m) ||
         edge(o.z(), angular_steps, angular_step);
}

Result<CellBox> CorrelativeSearch::cells_read(const GridGeometry& geo, std::span<const Vec2> points,
                                              const Pose& predicted, const SearchWindow& window,
                                              const SearchLattice& lattice) {
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x;
  double hi_x = -lo_x, hi_y = -lo_x;
  for (const Vec2& p : points) {
    const Vec2 g = geo.to_grid(predicted.transform(p));
    const double sweep = norm(p) * window.angular_rad / geo.resolution;  // arc length bounds the chord
    lo_x = std::min(lo_x, g.x - sweep);
    lo_y = std::min(lo_y, g.y - sweep);
    hi_x = std::max(hi_x, g.x + sweep);
    hi_y = std::max(hi_y, g.y + sweep);
  }
  const double limit = static_cast<double>(std::numeric_limits<int32_t>::max() / 4);
  if (!(std::abs(lo_x) < limit && std::abs(lo_y) < limit && std::abs(hi_x) < limit && std::abs(hi_y) < limit))
    return Error{"scan match: the search window lies off the grid"};
  const int32_t reach = lattice.linear_steps * lattice.step_cells;
  CellBox box{static_cast<int32_t>(std::floor(lo_x)) - reach, static_cast<int32_t>(std::floor(lo_y)) - reach,
              0, 0};
  box.width = static_cast<int32_t>(std::floor(hi_x)) + reach + 1 - box.x0;
  box.height = static_cast<int32_t>(std::floor(hi_y)) + reach + 1 - box.y0;
  if (box.x0 >= geo.width || box.y0 >= geo.height || box.x0 + box.width <= 0 || box.y0 + box.height <= 0)
    return Error{"scan match: the search window lies off the grid"};
  return box;
}

void CorrelativeSearch::score(const LikelihoodField& field, const GridGeometry& geo,
                              std::span<const Vec2> points, const Pose& predicted,
                              const SearchLattice& lattice) {
  const size_t n = points.size();
  const int32_t side = lattice.side(), step = lattice.step_cells, fw = field.width();
  const int32_t reach = lattice.linear_steps * lattice.step_cells;
  const size_t per_heading = lattice.per_heading();
  const std::span<const float> values = field.values();
  sums_.assign(lattice.size(), 0.0f);
  lookup_.resize(n);
  for (int32_t h = 0; h < lattice.headings(); ++h) {
    const double theta = predicted.theta + (h - lattice.angular_steps) * lattice.angular_step;
    const double c = std::cos(theta), s = std::sin(theta);
    for (size_t i = 0; i < n; ++i) {
      const Vec2 g = geo.to_grid(
          {predicted.x + c * points[i].x - s * points[i].y, predicted.y + s * points[i].x + c * points[i].y});
      const int32_t cx = static_cast<int32_t>(std::floor(g.x)) - field.box().x0 - reach;
      const int32_t cy = static_cast<int32_t>(std::floor(g.y)) - field.box().y0 - reach;
      lookup_[i] = cy * fw + cx;
    }
    float* sums = sums_.data() + static_cast<size_t>(h) * per_heading;
    for (size_t i = 0; i < n; ++i) {
      for (int32_t iy = 0; iy < side; ++iy) {
        const float* row = values.data() + lookup_[i] + iy * step * fw;
        float* out = sums + static_cast<size_t>(iy) * static_cast<size_t>(side);
        for (int32_t ix = 0; ix < side; ++ix) out[ix] += row[ix * step];
      }
    }
  }
}

size_t CorrelativeSearch::best(const SearchLattice& lattice, const Eigen::Vector3d& scale) const {
  // Along a straight wall or a corridor whole-cell shifts score exactly alike, and the first of them
  // (the window's corner) would push every such keyframe the same way.
  const float top = *std::max_element(sums_.begin(), sums_.end());
  const float tie = top - std::max(1e-5f * std::abs(top), 1e-6f);
  size_t best_index = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (size_t index = 0; index < sums_.size(); ++index) {
    if (sums_[index] < tie) continue;
    const double d = lattice.offset(index).cwiseProduct(scale).squaredNorm();
    if (d < best_distance) {
      best_distance = d;
      best_index = index;
    }
  }
  return best_index;
}

}  // namespace slam::correction
