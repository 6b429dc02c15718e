// The automatic fit decision (see auto_fit.hpp).
#include "viewer/core/auto_fit.hpp"

#include <algorithm>
#include <utility>

namespace slam::viewer {
namespace {

bool same(const Viewport& a, const Viewport& b) {
  return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
}

bool contains(const WorldBox& outer, const WorldBox& inner) {
  return inner.min_x >= outer.min_x && inner.min_y >= outer.min_y && inner.max_x <= outer.max_x &&
         inner.max_y <= outer.max_y;
}

// `box` grown to at least `min_side` per side, then by `slack` of its size on each side.
WorldBox padded(const WorldBox& box, double min_side, double slack) {
  WorldBox b = box;
  for (auto [lo, hi] : {std::pair{&b.min_x, &b.max_x}, std::pair{&b.min_y, &b.max_y}}) {
    const double side = std::max(*hi - *lo, min_side), mid = (*lo + *hi) / 2.0;
    *lo = mid - side * (0.5 + slack);
    *hi = mid + side * (0.5 + slack);
  }
  return b;
}

}  // namespace

WorldBox unite(const WorldBox& a, const WorldBox& b) {
  return {std::min(a.min_x, b.min_x), std::min(a.min_y, b.min_y), std::max(a.max_x, b.max_x),
          std::max(a.max_y, b.max_y)};
}

std::optional<WorldBox> AutoFit::update(const std::optional<WorldBox>& content,
                                        const std::optional<WorldBox>& grid, uint32_t layout_id,
                                        const Viewport& viewport, bool user_moved) {
  if (user_moved || (!content && !grid)) return std::nullopt;
  const Basis basis = content ? Basis::Content : Basis::Extent;
  const bool relaid = grid && layout_id != layout_id_;
  const bool refit = basis != basis_ || relaid || !same(viewport, viewport_) ||
                     !contains(fitted_, content ? *content : *grid);
  if (grid) layout_id_ = layout_id;
  viewport_ = viewport;
  if (!refit) return std::nullopt;
  basis_ = basis;
  fitted_ = content ? padded(*content, kMinSide, kSlack) : *grid;
  return fitted_;
}

}  // namespace slam::viewer
