// BucketNearestNeighbors answers exactly as OMPL's brute-force structure does.
#include "planner/core/ompl_planner_neighbors.hpp"

#include <gtest/gtest.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>

#include <random>
#include <vector>

namespace slam::planner {
namespace {

TEST(BucketNearestNeighbors, FindsWhatABruteForceSearchFinds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(-5.0, 15.0);
  std::uniform_real_distribution<double> y(2.0, 8.0);
  std::vector<Vec2> points;
  for (int i = 0; i < 500; ++i) points.push_back({x(rng), y(rng)});
  // Items are indices into `points`; the query item is the last point.
  const auto at = [&points](const size_t& i) { return points[i]; };
  BucketNearestNeighbors<size_t> buckets({-5.0, 2.0}, {20.0, 6.0}, 0.7, at);
  ompl::NearestNeighborsLinear<size_t> linear;
  linear.setDistanceFunction(
      [&](const size_t& a, const size_t& b) { return distance(points[a], points[b]); });
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    buckets.add(i);
    linear.add(i);
  }
  EXPECT_EQ(buckets.size(), points.size() - 1);
  ASSERT_TRUE(buckets.remove(3));
  ASSERT_TRUE(linear.remove(3));
  EXPECT_FALSE(buckets.remove(3));
  const size_t query = points.size() - 1;
  for (int trial = 0; trial < 50; ++trial) {
    points[query] = {x(rng), y(rng)};
    for (const size_t k : {size_t{1}, size_t{7}, size_t{40}}) {
      std::vector<size_t> got;
      std::vector<size_t> want;
      buckets.nearestK(query, k, got);
      linear.nearestK(query, k, want);
      EXPECT_EQ(got, want) << "trial " << trial << " k " << k;
    }
    std::vector<size_t> got;
    std::vector<size_t> want;
    buckets.nearestR(query, 1.3, got);
    linear.nearestR(query, 1.3, want);
    EXPECT_EQ(got, want) << "trial " << trial;
    EXPECT_EQ(buckets.nearest(query), linear.nearest(query));
  }
  std::vector<size_t> all;
  buckets.list(all);
  EXPECT_EQ(all.size(), points.size() - 2);
  buckets.clear();
  EXPECT_EQ(buckets.size(), 0u);
}

}  // namespace
}  // namespace slam::planner
