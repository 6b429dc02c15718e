#include "pose_correction/keyframe_index.hpp"

#include <cmath>

namespace slam::correction {

void KeyframeIndex::insert(uint32_t slot, Vec2 position) {
  const auto ix = static_cast<int32_t>(std::floor(position.x / cell_m_));
  const auto iy = static_cast<int32_t>(std::floor(position.y / cell_m_));
  buckets_[key(ix, iy)].push_back(slot);
}

void KeyframeIndex::near(Vec2 centre, double radius, std::vector<uint32_t>& out) const {
  const auto x0 = static_cast<int32_t>(std::floor((centre.x - radius) / cell_m_));
  const auto x1 = static_cast<int32_t>(std::floor((centre.x + radius) / cell_m_));
  const auto y0 = static_cast<int32_t>(std::floor((centre.y - radius) / cell_m_));
  const auto y1 = static_cast<int32_t>(std::floor((centre.y + radius) / cell_m_));
  for (int32_t iy = y0; iy <= y1; ++iy) {
    for (int32_t ix = x0; ix <= x1; ++ix) {
      const auto it = buckets_.find(key(ix, iy));
      if (it != buckets_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
    }
  }
}

}  // namespace slam::correction
