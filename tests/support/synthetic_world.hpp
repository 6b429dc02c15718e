#pragma once
// Synthetic worlds for SLAM tests and benches: walls as exact segments, rasterised into an
// occupancy grid of cell class octets (what the mapper publishes), and a sparse range sensor that
// casts rays against the exact walls (what a robot reports). Header-only; needs slam_core's headers.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "common/core/cell_class.hpp"
#include "common/core/geometry.hpp"

namespace slam::testkit {

struct Wall {
  Vec2 a;
  Vec2 b;
};

struct SyntheticWorld {
  std::vector<Wall> walls;

  void wall(Vec2 a, Vec2 b) { walls.push_back({a, b}); }
  // The four walls of the axis-aligned rectangle [lo, hi].
  void room(Vec2 lo, Vec2 hi) {
    wall(lo, {hi.x, lo.y});
    wall({hi.x, lo.y}, hi);
    wall(hi, {lo.x, hi.y});
    wall({lo.x, hi.y}, lo);
  }

  // Distance along the ray from `from` at heading `angle` to the nearest wall within max_range.
  std::optional<double> cast(Vec2 from, double angle, double max_range) const {
    const Vec2 d{std::cos(angle), std::sin(angle)};
    std::optional<double> nearest;
    for (const Wall& w : walls) {
      const Vec2 e = w.b - w.a;
      const double denom = cross(d, e);
      if (std::abs(denom) < 1e-12) continue;  // parallel
      const Vec2 rel = w.a - from;
      const double t = cross(rel, e) / denom;  // along the ray
      const double u = cross(rel, d) / denom;  // along the wall
      if (t > 0.0 && t <= max_range && u >= 0.0 && u <= 1.0 && (!nearest || t < *nearest)) nearest = t;
    }
    return nearest;
  }
};

// Three by two rooms of 4 x 4 m joined by 1 m doorways. Bare, the plan is the same turned by half a
// turn: callers add the furniture that tells rooms apart.
inline SyntheticWorld six_rooms() {
  SyntheticWorld w;
  w.room({0.0, 0.0}, {12.0, 8.0});
  for (double x : {4.0, 8.0}) {
    w.wall({x, 0.0}, {x, 1.5});
    w.wall({x, 2.5}, {x, 5.5});
    w.wall({x, 6.5}, {x, 8.0});
  }
  w.wall({0.0, 4.0}, {1.5, 4.0});
  w.wall({2.5, 4.0}, {9.5, 4.0});
  w.wall({10.5, 4.0}, {12.0, 4.0});
  return w;
}

// A grid over [lo, hi] whose cell centres lie on multiples of the resolution, so walls drawn at round
// coordinates run through cell centres and the rasterised map carries no half-cell bias.
inline GridGeometry centred_geometry(Vec2 lo, Vec2 hi, double resolution = 0.05) {
  GridGeometry g;
  g.resolution = resolution;
  g.origin = {lo.x - resolution / 2.0, lo.y - resolution / 2.0};
  g.width = static_cast<int32_t>(std::lround((hi.x - lo.x) / resolution)) + 1;
  g.height = static_cast<int32_t>(std::lround((hi.y - lo.y) / resolution)) + 1;
  return g;
}

// A grid of class octets: free everywhere, occupied in every cell a wall passes through.
struct ClassGrid {
  GridGeometry geometry;
  std::vector<uint8_t> classes;

  static ClassGrid rasterise(const SyntheticWorld& world, const GridGeometry& geometry) {
    ClassGrid g{geometry, std::vector<uint8_t>(geometry.cells(), kCellFree)};
    for (const Wall& w : world.walls) {
      const double length = distance(w.a, w.b);
      const int samples = static_cast<int>(std::ceil(length / (geometry.resolution / 4.0))) + 1;
      for (int i = 0; i < samples; ++i) {
        const Vec2 p = w.a + (w.b - w.a) * (static_cast<double>(i) / std::max(samples - 1, 1));
        if (const auto c = geometry.cell_at(p)) g.classes[geometry.index(*c)] = kCellOccupied;
      }
    }
    return g;
  }
};

// A sparse robot sensor: `beams` rays spread evenly over a full turn with a random phase per
// message, range noise of `noise_m` (Gaussian), hits only (misses report nothing, like v1 robots).
struct SparseSensor {
  int beams = 10;
  double max_range_m = 6.0;
  double noise_m = 0.0;

  // Appends the hits seen from `pose` (world frame) to `out`, expressed in `frame`'s coordinates.
  void observe(const SyntheticWorld& world, const Pose& pose, const Pose& frame, std::mt19937& rng,
               std::vector<Vec2>& out) const {
    std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi / beams);
    std::normal_distribution<double> noise(0.0, noise_m);
    const double start = phase(rng);
    const Pose frame_from_world = frame.inverse();
    for (int b = 0; b < beams; ++b) {
      const double angle = pose.theta + start + 2.0 * std::numbers::pi * b / beams;
      const auto range = world.cast(pose.position(), angle, max_range_m);
      if (!range) continue;
      const double measured = *range + (noise_m > 0.0 ? noise(rng) : 0.0);
      const Vec2 hit{pose.x + measured * std::cos(angle), pose.y + measured * std::sin(angle)};
      out.push_back(frame_from_world.transform(hit));
    }
  }
};

// A keyframe as the mapper gathers it: `messages` sensor readings taken while the robot drives
// from `start` by `step` per message, every point in the frame of the first pose.
inline std::vector<Vec2> keyframe_points(const SyntheticWorld& world, const SparseSensor& sensor,
                                         const Pose& start, const Pose& step, int messages,
                                         std::mt19937& rng) {
  std::vector<Vec2> points;
  Pose pose = start;
  for (int m = 0; m < messages; ++m) {
    sensor.observe(world, pose, start, rng, points);
    pose = pose.compose(step);
  }
  return points;
}

}  // namespace slam::testkit
