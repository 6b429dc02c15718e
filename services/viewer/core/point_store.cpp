// Append-only point storage with a generation counter (see point_store.hpp).
#include "viewer/core/point_store.hpp"

#include <algorithm>

namespace slam::viewer {

size_t PointStore::append(const float* xy, size_t n) {
  const size_t room = max_points_ - std::min(max_points_, size());
  const size_t take = std::min(n, room);
  dropped_ += n - take;
  if (take == 0) return 0;
  if (xy_.empty()) bounds_ = {xy[0], xy[1], xy[0], xy[1]};
  for (size_t i = 0; i < take; ++i) {
    const double x = xy[2 * i], y = xy[2 * i + 1];
    bounds_.min_x = std::min(bounds_.min_x, x);
    bounds_.max_x = std::max(bounds_.max_x, x);
    bounds_.min_y = std::min(bounds_.min_y, y);
    bounds_.max_y = std::max(bounds_.max_y, y);
  }
  xy_.insert(xy_.end(), xy, xy + 2 * take);
  return take;
}

void PointStore::reset() {
  xy_.clear();
  xy_.shrink_to_fit();
  bounds_ = {};
  ++generation_;
}

void PointStore::move_all(const Pose& delta) {
  std::vector<float> moved;
  moved.swap(xy_);
  bounds_ = {};
  for (size_t i = 0; i + 1 < moved.size(); i += 2) {
    const Vec2 p = delta.transform({moved[i], moved[i + 1]});
    moved[i] = static_cast<float>(p.x);
    moved[i + 1] = static_cast<float>(p.y);
  }
  append(moved.data(), moved.size() / 2);
  ++generation_;
}

PointStore::Range PointStore::last_n(size_t n) const {
  const size_t total = size();
  if (n == 0 || n >= total) return {0, total};
  return {total - n, n};
}

}  // namespace slam::viewer
