// World geometry: ray casts (against a brute-force reference over every wall), clearance and
// motion checks, the built-in worlds, and occupancy images turned into merged walls.
#include "simulator/core/world.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "simulator/core/builtin_worlds.hpp"
#include "simulator/core/world_image.hpp"

namespace slam::sim {
namespace {

using ::testing::HasSubstr;

World make(Bounds b, std::vector<Segment> walls) {
  auto w = World::create("test", b, std::move(walls));
  EXPECT_TRUE(w) << w.message();
  return std::move(*w);
}

double brute_cast(const World& w, Vec2 o, Vec2 d, double max_range) {
  double best = max_range;
  for (const Segment& s : w.walls()) best = std::min(best, ray_segment(o, d, s));
  return best;
}

TEST(RayCast, HitsSegmentAtExactDistance) {
  const World w = make({{0, 0}, {10, 10}}, {{{5, 2}, {5, 8}}});
  EXPECT_DOUBLE_EQ(w.cast({1, 5}, {1, 0}, 20.0), 4.0);
  EXPECT_DOUBLE_EQ(w.cast({1, 5}, {-1, 0}, 20.0), 1.0);  // left border
  EXPECT_DOUBLE_EQ(w.cast({1, 5}, {1, 0}, 3.0), 3.0);    // out of range: max_range
  EXPECT_NEAR(w.cast({1, 1}, {std::sqrt(0.5), std::sqrt(0.5)}, 20.0), std::sqrt(2.0) * 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(w.cast({6, 9}, {0, -1}, 20.0), 9.0);  // passes beside the wall to the bottom
}

TEST(RayCast, SegmentEndpointsAndParallelRays) {
  const Segment s{{2, 0}, {2, 2}};
  EXPECT_DOUBLE_EQ(ray_segment({0, 2}, {1, 0}, s), 2.0);  // grazes the end point: a hit
  EXPECT_TRUE(std::isinf(ray_segment({0, 2.001}, {1, 0}, s)));
  EXPECT_TRUE(std::isinf(ray_segment({2, -1}, {0, 1}, s)));  // collinear
  EXPECT_TRUE(std::isinf(ray_segment({3, 1}, {1, 0}, s)));   // behind the origin
}

TEST(RayCast, CircleHitsAndMisses) {
  EXPECT_DOUBLE_EQ(ray_circle({0, 0}, {1, 0}, {5, 0}, 1.0), 4.0);
  EXPECT_TRUE(std::isinf(ray_circle({0, 0}, {-1, 0}, {5, 0}, 1.0)));
  EXPECT_TRUE(std::isinf(ray_circle({0, 0}, {1, 0}, {5, 2}, 1.0)));
  EXPECT_DOUBLE_EQ(ray_circle({5, 0.5}, {1, 0}, {5, 0}, 1.0), 0.0);  // starts inside
}

TEST(RayCast, GridIndexMatchesBruteForce) {
  // Many random walls of all orientations in a world larger than one index cell.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 30.0);
  std::vector<Segment> walls;
  for (int i = 0; i < 300; ++i) walls.push_back({{u(rng), u(rng)}, {u(rng), u(rng)}});
  for (int i = 0; i < 100; ++i) {
    const double x = u(rng), y = u(rng);
    walls.push_back({{x, y}, {x + 0.5, y}});
    walls.push_back({{x, y}, {x, y + 0.5}});
  }
  walls.erase(std::remove_if(walls.begin(), walls.end(),
                             [](const Segment& s) {
                               return s.a.x > 30.5 || s.a.y > 30.5 || s.b.x > 30.5 || s.b.y > 30.5;
                             }),
              walls.end());
  const World w = make({{0, 0}, {30.5, 30.5}}, walls);
  std::uniform_real_distribution<double> ua(-std::numbers::pi, std::numbers::pi);
  for (int i = 0; i < 20000; ++i) {
    const Vec2 o{u(rng), u(rng)};
    const double a = i % 50 == 0 ? std::numbers::pi / 2 * (i % 4) : ua(rng);  // some axis-aligned beams
    const Vec2 d{std::cos(a), std::sin(a)};
    const double range = i % 2 ? 4.0 : 50.0;
    ASSERT_DOUBLE_EQ(w.cast(o, d, range), brute_cast(w, o, d, range)) << "ray " << i;
  }
}

TEST(RayCast, RayFromOutsideTheGridStillHits) {
  const World w = make({{0, 0}, {4, 4}}, {});
  EXPECT_DOUBLE_EQ(w.cast({-2, 1}, {1, 0}, 10.0), 2.0);
  EXPECT_DOUBLE_EQ(w.cast({-2, 1}, {-1, 0}, 10.0), 10.0);
}

TEST(World, ClearanceAndMotion) {
  const World w = make({{0, 0}, {10, 10}}, {{{5, 0}, {5, 6}}});
  EXPECT_TRUE(w.is_free({4.5, 3}, 0.4));
  EXPECT_FALSE(w.is_free({4.7, 3}, 0.4));
  EXPECT_FALSE(w.is_free({0.1, 3}, 0.2));  // border wall
  EXPECT_FALSE(w.is_free({-1, 3}, 0.2));   // outside
  EXPECT_TRUE(w.is_free({5, 6.5}, 0.4));   // past the wall's end
  EXPECT_TRUE(w.motion_clear({4, 3}, {4.5, 3}, 0.4));
  EXPECT_FALSE(w.motion_clear({4, 3}, {6, 3}, 0.1));  // through the wall
  EXPECT_FALSE(w.motion_clear({4.5, 3}, {4.7, 3}, 0.4));
}

TEST(World, RejectsBadGeometry) {
  EXPECT_THAT(World::create("w", {{0, 0}, {0, 5}}, {}).message(), HasSubstr("must be positive"));
  EXPECT_THAT(World::create("w", {{0, 0}, {NAN, 5}}, {}).message(), HasSubstr("not finite"));
  EXPECT_THAT(World::create("w", {{0, 0}, {1e6, 5}}, {}).message(), HasSubstr("exceeds"));
  EXPECT_THAT(World::create("w", {{0, 0}, {5, 5}}, {{{1, 1}, {6, 1}}}).message(), HasSubstr("wall 1"));
  EXPECT_THAT(World::create("w", {{0, 0}, {5, 5}}, {{{1, 1}, {INFINITY, 1}}}).message(),
              HasSubstr("non-finite"));
}

TEST(BuiltinWorlds, AllNamesLoad) {
  for (auto name : builtin_world_names()) {
    const auto w = builtin_world(name);
    ASSERT_TRUE(w) << name << ": " << w.message();
    EXPECT_EQ(w->name(), name);
  }
  EXPECT_THAT(builtin_world("mars").message(), HasSubstr("unknown built-in world 'mars'"));
}

TEST(BuiltinWorlds, OfficeIsAboutTwentyByFifteenWithRoomsAndDoors) {
  const auto w = builtin_world("office");
  ASSERT_TRUE(w);
  EXPECT_DOUBLE_EQ(w->bounds().width(), 20.0);
  EXPECT_DOUBLE_EQ(w->bounds().height(), 15.0);
  // From the corridor, a beam through a door reaches the far wall of the room; beside it, the wall.
  EXPECT_DOUBLE_EQ(w->cast({12.5, 7.5}, {0, -1}, 20.0), 7.5);
  EXPECT_DOUBLE_EQ(w->cast({14.0, 7.5}, {0, -1}, 20.0), 1.5);
  EXPECT_FALSE(w->is_free({11.5, 13.0}, 0.1));  // inside the meeting table
}

TEST(BuiltinWorlds, TrackIsARingCorridor) {
  const auto w = builtin_world("track");
  ASSERT_TRUE(w);
  // From the middle of the corridor, outward and inward walls are about 0.5 m away everywhere.
  for (int k = 0; k < 16; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 16 + 0.1;
    const Vec2 p{3.0 + 2.0 * std::cos(a), 3.0 + 2.0 * std::sin(a)};
    EXPECT_NEAR(w->cast(p, {std::cos(a), std::sin(a)}, 5.0), 0.5, 0.01);
    EXPECT_NEAR(w->cast(p, {-std::cos(a), -std::sin(a)}, 5.0), 0.5, 0.01);
    EXPECT_TRUE(w->is_free(p, 0.3));
  }
  EXPECT_FALSE(w->is_free({3.0, 3.0}, 0.1));  // inside the inner circle: solid
  EXPECT_FALSE(w->is_free({0.3, 0.3}, 0.1));  // outside the track: solid
}

// Every point of a `step` lattice a robot of `radius` can drive to from `start` (4-neighbour moves).
std::vector<Vec2> reachable(const World& w, Vec2 start, double radius, double step) {
  const Bounds& b = w.bounds();
  const int nx = static_cast<int>(b.width() / step), ny = static_cast<int>(b.height() / step);
  const auto at = [&](int x, int y) { return Vec2{b.min.x + (x + 0.5) * step, b.min.y + (y + 0.5) * step}; };
  std::vector<char> seen(static_cast<size_t>(nx * ny), 0);
  std::vector<std::pair<int, int>> todo{
      {static_cast<int>((start.x - b.min.x) / step), static_cast<int>((start.y - b.min.y) / step)}};
  std::vector<Vec2> out;
  if (!w.is_free(at(todo[0].first, todo[0].second), radius)) return out;
  seen[static_cast<size_t>(todo[0].second * nx + todo[0].first)] = 1;
  while (!todo.empty()) {
    const auto [x, y] = todo.back();
    todo.pop_back();
    out.push_back(at(x, y));
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int u = x + dx, v = y + dy;
      if (u < 0 || v < 0 || u >= nx || v >= ny || seen[static_cast<size_t>(v * nx + u)]) continue;
      if (!w.motion_clear(at(x, y), at(u, v), radius)) continue;
      seen[static_cast<size_t>(v * nx + u)] = 1;
      todo.push_back({u, v});
    }
  }
  return out;
}

TEST(BuiltinWorlds, RoomsAreIdenticalAndEveryOneIsReachableFromTheCorridor) {
  const auto w = builtin_world("rooms");
  ASSERT_TRUE(w) << w.message();
  EXPECT_DOUBLE_EQ(w->bounds().width(), 12.0);
  EXPECT_DOUBLE_EQ(w->bounds().height(), 8.0);
  const auto free = reachable(*w, {6.0, 1.0}, 0.15, 0.1);
  for (int k = 0; k < 4; ++k) {
    const double x0 = 3.0 * k;
    // Somewhere in each room's back half, behind its table, is reachable.
    const bool reached = std::any_of(free.begin(), free.end(), [&](Vec2 p) {
      return p.x > x0 + 0.5 && p.x < x0 + 2.5 && p.y > 6.5 && p.y < 7.5;
    });
    EXPECT_TRUE(reached) << "room " << k;
    // The same scan from the same spot in every room: identical rooms tempt a wrong loop closure.
    for (int beam = 0; beam < 16; ++beam) {
      const double a = 2.0 * std::numbers::pi * beam / 16 + 0.05;
      const Vec2 dir{std::cos(a), std::sin(a)};
      EXPECT_NEAR(w->cast({x0 + 1.5, 4.0}, dir, 4.0), w->cast({1.5, 4.0}, dir, 4.0), 1e-9)
          << "room " << k << " beam " << beam;
    }
  }
  EXPECT_FALSE(w->is_free({1.5, 5.0}, 0.1));  // inside the first room's table
  EXPECT_FALSE(w->is_free({9.2, 7.0}, 0.1));  // inside the last room's shelf
}

TEST(BuiltinWorlds, MazeIsTheSameEveryTime) {
  const auto a = builtin_world("maze"), b = builtin_world("maze");
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->walls().size(), b->walls().size());
  // A perfect 10x10 maze has 100 - 1 open passages of the 180 inner walls.
  EXPECT_EQ(a->walls().size(), 4u + 180u - 99u);
}

TEST(ImageWorld, MergesExposedEdgesIntoLongWalls) {
  // 6x4 image, a 3x2 occupied block at columns 1..3, rows 1..2.
  OccupancyImage img;
  img.width = 6;
  img.height = 4;
  img.resolution = 0.5;
  img.origin = {-1.0, 2.0};
  img.occupied.assign(24, 0);
  for (int y = 1; y <= 2; ++y)
    for (int x = 1; x <= 3; ++x) img.occupied[static_cast<size_t>(y * 6 + x)] = 1;
  const auto w = world_from_image(img, "img");
  ASSERT_TRUE(w) << w.message();
  ASSERT_EQ(w->walls().size(), 4u + 4u);  // borders + the block's four sides, one segment each
  EXPECT_DOUBLE_EQ(w->bounds().min.x, -1.0);
  EXPECT_DOUBLE_EQ(w->bounds().max.y, 4.0);
  // The block spans x in [-0.5, 1.0], y in [2.5, 3.5].
  EXPECT_DOUBLE_EQ(w->cast({-0.9, 3.0}, {1, 0}, 10.0), 0.4);
  EXPECT_DOUBLE_EQ(w->cast({0.0, 2.1}, {0, 1}, 10.0), 0.4);
  EXPECT_FALSE(w->is_free({0.0, 3.0}, 0.01));  // inside the block
  EXPECT_TRUE(w->is_free({1.5, 3.0}, 0.2));
}

TEST(ImageWorld, AdjacentBlocksShareNoInnerWall) {
  OccupancyImage img;
  img.width = 3;
  img.height = 1;
  img.resolution = 1.0;
  img.occupied = {1, 1, 0};
  const auto w = world_from_image(img, "row");
  ASSERT_TRUE(w) << w.message();
  EXPECT_EQ(w->walls().size(), 4u + 1u);  // only the edge between column 1 and 2
}

TEST(ImageWorld, RejectsInconsistentImages) {
  OccupancyImage img;
  img.width = 2;
  img.height = 2;
  img.occupied = {0, 0, 0};
  EXPECT_THAT(world_from_image(img, "m").message(), HasSubstr("3 occupancy flags for a 2x2 image"));
  img.occupied.push_back(0);
  img.resolution = 0.0;
  EXPECT_THAT(world_from_image(img, "m").message(), HasSubstr("resolution"));
  img.resolution = 0.05;
  img.width = 0;
  EXPECT_THAT(world_from_image(img, "m").message(), HasSubstr("image size"));
}

}  // namespace
}  // namespace slam::sim
