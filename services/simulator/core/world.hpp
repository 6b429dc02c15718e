#pragma once
// The hidden world robots drive in: wall segments in metres inside rectangular bounds (whose four
// border walls are always part of the world), indexed by a uniform grid so beams and collision
// checks only look at nearby walls.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/core/result.hpp"
#include "simulator/core/geometry.hpp"
#include "simulator/core/grid.hpp"

namespace slam::sim {

// Row-major occupancy flags; row 0 is the bottom row (y = origin.y), column 0 is x = origin.x.
struct OccupancyImage {
  int width = 0;
  int height = 0;
  double resolution = 0.05;       // metres per cell
  Vec2 origin;                    // map-frame position of the bottom-left corner of cell (0, 0)
  std::vector<uint8_t> occupied;  // width * height flags, non-zero = occupied

  // True when p falls in an occupied cell (outside the image counts as not occupied).
  bool occupied_at(Vec2 p) const;
};

class World {
 public:
  // Largest accepted side length (metres): bigger worlds are input mistakes (cm taken for mm).
  static constexpr double kMaxExtent = 10'000.0;

  // Validates the bounds (finite, positive, at most kMaxExtent) and that every wall is finite and
  // inside them, then adds the four border walls and builds the index. `solid` marks filled areas
  // that walls only outline (empty image: none); is_free() is false inside them.
  static Result<World> create(std::string name, Bounds bounds, std::vector<Segment> walls,
                              OccupancyImage solid = {});

  const std::string& name() const { return name_; }
  const Bounds& bounds() const { return bounds_; }
  // Every wall including the four borders (the borders come first).
  std::span<const Segment> walls() const { return walls_; }
  const GridGeometry& grid() const { return grid_; }

  // Distance along the unit-length ray to the nearest wall, or max_range when none is closer.
  double cast(Vec2 origin, Vec2 dir, double max_range) const;

  // True when p is inside the bounds, not in a solid cell, and no wall is closer than radius.
  bool is_free(Vec2 p, double radius) const;

  // True when a disc of `radius` can slide straight from `from` to `to`: the path crosses no wall
  // and the end has clearance (steps are short next to the radius, so this cannot tunnel).
  bool motion_clear(Vec2 from, Vec2 to, double radius) const;

 private:
  World() = default;
  void build_index();

  std::string name_;
  Bounds bounds_;
  std::vector<Segment> walls_;
  GridGeometry grid_;
  Buckets index_;
  OccupancyImage solid_;
};

}  // namespace slam::sim
