#pragma once
// One robot's measurement points, append-only and flat (x, y floats) so the GPU layer can
// upload just what was added since its last look; reset() bumps a generation so it knows to
// start over. Bounded: beyond max_points new points are counted and dropped.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "viewer/core/view_transform.hpp"

namespace slam::viewer {

class PointStore {
 public:
  explicit PointStore(size_t max_points = size_t{16} << 20) : max_points_(max_points) {}

  // Appends n points from xy (2n floats); returns how many were stored.
  size_t append(const float* xy, size_t n);
  void reset();
  // Moves every stored point by `delta` (a new generation: whoever uploaded them starts over).
  void move_all(const Pose& delta);

  size_t size() const { return xy_.size() / 2; }
  const float* data() const { return xy_.data(); }
  uint64_t generation() const { return generation_; }
  uint64_t dropped() const { return dropped_; }
  bool empty() const { return xy_.empty(); }
  // Bounding box of every stored point (meaningless when empty()).
  const WorldBox& bounds() const { return bounds_; }

  struct Range {
    size_t first = 0;
    size_t count = 0;
  };
  // The newest `n` points (all when n == 0 or n >= size()).
  Range last_n(size_t n) const;

 private:
  size_t max_points_;
  std::vector<float> xy_;
  uint64_t generation_ = 0;
  uint64_t dropped_ = 0;
  WorldBox bounds_;
};

}  // namespace slam::viewer
