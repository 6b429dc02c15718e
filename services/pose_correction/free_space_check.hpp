#pragma once
// A check a placement must pass besides its points landing on walls: the free space its rays swept
// must not cross the map's walls. A look-alike place (a room's mirror image, an office wing turned
// half round) can put most points on some wall while the rays to them run through others; the
// correlative score alone cannot tell, since it reads only where rays end.
#include <cstddef>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"
#include "pose_correction/grid_view.hpp"

namespace slam::correction {

struct Ray {
  Vec2 origin;  // where the robot was, in the searched points' frame
  Vec2 end;     // what it hit
};

// A ray's last stretch may pass a wall seen a little off without counting as a crossing: a search's
// lattice (a cell, a heading step) and walls a cell or two thick.
inline constexpr double kWallCrossingMargin_m = 0.3;

// Keeps every stride-th ray, the stride chosen so that at most `max_rays` are left (0: all): a
// search's cost follows its points, and a few hundred spread over a trail pin a place.
void thin_evenly(std::vector<Ray>& rays, size_t max_rays);

// The share (0..1) of `rays`, moved by `pose` onto `map`, that cross a wall cell of the map before
// the last `end_margin_m` of their length (a wall seen a little off is not a crossing). Rays off
// the map or shorter than the margin count as not crossing. 0 when there are no rays.
double crossed_wall_share(const GridView& map, const Pose& pose, std::span<const Ray> rays,
                          double end_margin_m);

}  // namespace slam::correction
