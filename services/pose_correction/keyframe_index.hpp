#pragma once
// Which keyframes lie near a point of the map: a uniform hash grid over the keyframes' current map
// positions, rebuilt after each graph optimisation moves them. Loop closure asks it for the old
// keyframes around a robot's predicted pose.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "common/core/geometry.hpp"

namespace slam::correction {

class KeyframeIndex {
 public:
  explicit KeyframeIndex(double cell_m = 1.0) : cell_m_(cell_m) {}

  void insert(uint32_t slot, Vec2 position);
  void clear() { buckets_.clear(); }
  // Appends to `out` the slots of keyframes whose position lies within `radius` of `centre`
  // (bucket-accurate: the caller filters by exact distance if it needs to).
  void near(Vec2 centre, double radius, std::vector<uint32_t>& out) const;

 private:
  static uint64_t key(int32_t ix, int32_t iy) {
    return (static_cast<uint64_t>(static_cast<uint32_t>(ix)) << 32) | static_cast<uint32_t>(iy);
  }
  double cell_m_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> buckets_;
};

}  // namespace slam::correction
