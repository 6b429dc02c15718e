#include "pose_correction/free_space_check.hpp"

#include <cmath>

#include "common/core/cell_class.hpp"

namespace slam::correction {
namespace {

bool crosses_wall(const GridView& map, Vec2 from, Vec2 to, double end_margin_m) {
  const GridGeometry& g = map.geometry;
  const double length = distance(from, to);
  const double reach = length - end_margin_m;
  if (reach <= 0.0) return false;
  // Half-cell steps visit every cell a ray passes through closely enough for walls a cell thick.
  const double step = 0.5 * g.resolution;
  const Vec2 dir{(to.x - from.x) / length, (to.y - from.y) / length};
  for (double s = 0.0; s < reach; s += step) {
    const auto cell = g.cell_at({from.x + dir.x * s, from.y + dir.y * s});
    if (cell && is_wall(map.classes[g.index(*cell)])) return true;
  }
  return false;
}

}  // namespace

double crossed_wall_share(const GridView& map, const Pose& pose, std::span<const Ray> rays,
                          double end_margin_m) {
  if (rays.empty() || map.geometry.cells() == 0) return 0.0;
  size_t crossed = 0;
  for (const Ray& r : rays)
    if (crosses_wall(map, pose.transform(r.origin), pose.transform(r.end), end_margin_m)) ++crossed;
  return static_cast<double>(crossed) / static_cast<double>(rays.size());
}

void thin_evenly(std::vector<Ray>& rays, size_t max_rays) {
  if (max_rays == 0 || rays.size() <= max_rays) return;
  const size_t stride = (rays.size() + max_rays - 1) / max_rays;
  size_t kept = 0;
  for (size_t i = 0; i < rays.size(); i += stride) rays[kept++] = rays[i];
  rays.resize(kept);
}

}  // namespace slam::correction
