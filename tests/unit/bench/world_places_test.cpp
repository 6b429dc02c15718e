#include "eval/world_places.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "simulator/core/builtin_worlds.hpp"

namespace slam::bench {
namespace {

TEST(WorldPlaces, ReachablePlacesKeepTheirClearanceAndStayInTheWorld) {
  auto world = sim::builtin_world("office");
  ASSERT_TRUE(world);
  const std::vector<Vec2> places = reachable_places(*world, {2.0, 7.5}, 0.35);
  ASSERT_GT(places.size(), 100u);
  for (const Vec2& p : places) {
    EXPECT_TRUE(world->is_free(p, 0.35)) << p.x << ", " << p.y;
    EXPECT_TRUE(world->bounds().contains(p));
  }
}

TEST(WorldPlaces, APatrolRouteTakesEveryLegAtLeastTheShortestTrip) {
  auto world = sim::builtin_world("office");
  ASSERT_TRUE(world);
  const std::vector<Vec2> places = reachable_places(*world, {2.0, 7.5}, 0.35);
  std::mt19937_64 rng(7);
  const Vec2 from{2.0, 7.5};
  const std::vector<Vec2> route = patrol_route(places, from, 8, 2.0, rng);
  ASSERT_EQ(route.size(), 8u);
  Vec2 previous = from;
  for (const Vec2& p : route) {
    EXPECT_NE(std::find(places.begin(), places.end(), p), places.end());
    EXPECT_GE(distance(p, previous), 2.0);
    previous = p;
  }
  std::mt19937_64 again(7);
  EXPECT_EQ(patrol_route(places, from, 8, 2.0, again), route) << "the same seed gives the same patrol";
}

TEST(WorldPlaces, WithOnePlaceThePatrolStaysThere) {
  const std::vector<Vec2> places = {{1.0, 1.0}};
  std::mt19937_64 rng(1);
  const std::vector<Vec2> route = patrol_route(places, {0.0, 0.0}, 3, 2.0, rng);
  ASSERT_EQ(route.size(), 3u);
  for (const Vec2& p : route) EXPECT_EQ(p, (Vec2{1.0, 1.0}));
}

}  // namespace
}  // namespace slam::bench
