#pragma once
// The pose corrector tests' world: walls as segments (a 6 x 5 m room with an L-shaped inner wall and
// a pillar: enough structure to pin x, y and theta), rays cast against them, and the walls drawn
// into class octets (occupied = 2) at 5 cm with cell centres on the walls (the matcher puts a point
// on the centre of its cell: walls on cell edges would shift the map).
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <vector>

#include "common/core/geometry.hpp"
#include "pose_correction/grid_view.hpp"
#include "synthetic_world.hpp"

namespace slam::correction::testing_scene {

struct Wall {
  Vec2 a, b;
};

inline std::vector<Wall> room() {
  return {{{0, 0}, {6, 0}}, {{6, 0}, {6, 5}},   {{6, 5}, {0, 5}},   {{0, 5}, {0, 0}},
          {{2, 2}, {4, 2}}, {{4, 2}, {4, 3.5}}, {{1, 4}, {1.4, 4}}, {{1.4, 4}, {1.4, 4.4}}};
}

// Distance along the ray from `origin` in direction `dir` (unit) to the nearest wall within `range`.
inline std::optional<double> cast(const std::vector<Wall>& walls, Vec2 origin, Vec2 dir, double range) {
  std::optional<double> best;
  for (const Wall& w : walls) {
    const Vec2 e = w.b - w.a;
    const double denom = cross(dir, e);
    if (std::abs(denom) < 1e-12) continue;
    const Vec2 d = w.a - origin;
    const double t = cross(d, e) / denom, u = cross(d, dir) / denom;
    if (t > 0 && t <= range && u >= 0 && u <= 1 && (!best || t < *best)) best = t;
  }
  return best;
}

// A laser's hits (`beams` over 360 degrees, `range` m) seen from `truth`, in the odometry frame of a
// robot that believes it is at `belief`.
inline std::vector<Vec2> laser_hits(const std::vector<Wall>& walls, const Pose& truth, const Pose& belief,
                                    int beams = 180, double range = 8.0) {
  std::vector<Vec2> hits;
  const Pose belief_from_truth = belief.compose(truth.inverse());
  for (int i = 0; i < beams; ++i) {
    const double a = truth.theta + 2.0 * std::numbers::pi * i / beams;
    const Vec2 dir{std::cos(a), std::sin(a)};
    if (auto t = cast(walls, truth.position(), dir, range))
      hits.push_back(belief_from_truth.transform(truth.position() + dir * *t));
  }
  return hits;
}

// The walls drawn into class octets; by default over the room and a margin.
struct WallMap {
  GridGeometry geometry;
  std::vector<uint8_t> cells;
  explicit WallMap(const std::vector<Wall>& walls, const GridGeometry& g = {{-0.525, -0.525}, 0.05, 140, 120})
      : geometry(g), cells(g.cells(), 0) {
    for (const Wall& w : walls) {
      const int steps = static_cast<int>(distance(w.a, w.b) / 0.01) + 1;
      for (int i = 0; i <= steps; ++i) {
        const Vec2 p = w.a + (w.b - w.a) * (static_cast<double>(i) / steps);
        if (auto c = geometry.cell_at(p)) cells[geometry.index(*c)] = 2;
      }
    }
  }
  GridView view() const { return {geometry, cells}; }
};

}  // namespace slam::correction::testing_scene
