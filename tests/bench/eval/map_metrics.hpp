#pragma once
// Quality of an exported map (MapImage, map frame) against the true walls (segments, same frame):
// how many occupied cells lie on a real wall, how far they lie from one, how much of the real walls
// the map found, and how much of the space the robots could reach the map knows to be free.
#include <cstddef>
#include <span>
#include <vector>

#include "common/core/map_io.hpp"
#include "common/core/result.hpp"
#include "simulator/core/geometry.hpp"

namespace slam::bench {

struct WallScores {
  size_t occupied_cells = 0;
  double near_wall_share = 0.0;       // occupied cells whose centre is within 1.5 cells of a true wall
  double mean_wall_distance_m = 0.0;  // mean distance of occupied cell centres to the nearest true wall
  double wall_found_share = 0.0;      // true wall length with an occupied cell centre within 1 cell
};

// Occupied cells against `walls`. The map must be axis-aligned (origin yaw 0, as exports are).
Result<WallScores> score_walls(const MapImage& map, std::span<const sim::Segment> walls);

struct CoverageScore {
  size_t reachable_cells = 0;  // cells a 4-connected walk from a start reaches without touching a wall
  size_t known_free = 0;       // of those, free in the map
  double share() const {
    return reachable_cells == 0 ? 0.0
                                : static_cast<double>(known_free) / static_cast<double>(reachable_cells);
  }
};

// Rasterises `walls` on the map's cell lattice (a cell any wall touches is blocked), floods the
// free cells from `starts` (the robots' true start positions), and counts how many of the reached
// cells the map shows free. The lattice covers the walls' extent, whatever part the map spans.
Result<CoverageScore> reachable_coverage(const MapImage& map, std::span<const sim::Segment> walls,
                                         std::span<const Vec2> starts);

// True when segment `s` shares a point with the closed square [lo, hi] (exposed for the tests).
bool segment_touches_box(const sim::Segment& s, Vec2 lo, Vec2 hi);

}  // namespace slam::bench
