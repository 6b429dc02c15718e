// GridAstar against a brute-force Dijkstra with the same move rules, plus the failure cases.
#include "planner/core/grid_astar.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <queue>
#include <random>

#include "grid_builder.hpp"

namespace slam::planner {
namespace {

// Reference: plain Dijkstra, 8-connected, no corner cutting, same unknown costs.
double dijkstra(const PlanningGrid& g, Cell s, Cell t, const AstarOptions& o) {
  const int w = g.width();
  const int h = g.height();
  std::vector<double> dist(g.cells().size(), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
  auto pass = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && !g.impassable({x, y}, o.unknown);
  };
  auto factor = [&](int x, int y) { return g.unknown({x, y}) ? o.unknown_cost_factor : 1.0; };
  dist[g.index(s)] = 0.0;
  q.push({0.0, g.index(s)});
  while (!q.empty()) {
    auto [d, i] = q.top();
    q.pop();
    if (d > dist[i]) continue;
    const Cell c = g.cell_of(i);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !pass(c.x + dx, c.y + dy)) continue;
        if (dx != 0 && dy != 0 && (!pass(c.x + dx, c.y) || !pass(c.x, c.y + dy))) continue;
        const double step = (dx != 0 && dy != 0 ? std::sqrt(2.0) : 1.0) * factor(c.x + dx, c.y + dy);
        const size_t ni = g.index({c.x + dx, c.y + dy});
        if (d + step < dist[ni]) {
          dist[ni] = d + step;
          q.push({dist[ni], ni});
        }
      }
    }
  }
  return dist[g.index(t)];
}

PlanningGrid random_grid(std::mt19937& rng, int w, int h, double blocked, double unknown) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<uint8_t> cells(static_cast<size_t>(w * h));
  for (auto& c : cells) {
    const double r = u(rng);
    c = r < blocked ? kCellOccupied : (r < blocked + unknown ? kCellUnknown : kCellFree);
  }
  PlanningGrid g;
  EXPECT_TRUE(g.reset({{}, 1.0, w, h}, 1, 0, cells));
  return g;
}

void expect_valid_path(const PlanningGrid& g, const std::vector<Cell>& path, const AstarOptions& o) {
  for (size_t i = 0; i < path.size(); ++i) {
    EXPECT_FALSE(g.impassable(path[i], o.unknown));
    if (i == 0) continue;
    const int dx = path[i].x - path[i - 1].x;
    const int dy = path[i].y - path[i - 1].y;
    ASSERT_LE(std::abs(dx), 1);
    ASSERT_LE(std::abs(dy), 1);
    if (dx != 0 && dy != 0) {
      EXPECT_FALSE(g.impassable({path[i - 1].x + dx, path[i - 1].y}, o.unknown));
      EXPECT_FALSE(g.impassable({path[i - 1].x, path[i - 1].y + dy}, o.unknown));
    }
  }
}

TEST(GridAstar, MatchesDijkstraOnRandomGrids) {
  std::mt19937 rng(7);
  GridAstar astar;  // one instance: also checks that reused buffers give fresh answers
  std::vector<Cell> path;
  int solved = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int w = 4 + static_cast<int>(rng() % 20);
    const int h = 4 + static_cast<int>(rng() % 20);
    const AstarOptions o{trial % 2 == 0 ? UnknownPolicy::Blocked : UnknownPolicy::Allowed,
                         1.0 + 0.5 * static_cast<double>(rng() % 6)};
    const PlanningGrid g = random_grid(rng, w, h, 0.3, 0.15);
    const Cell s{static_cast<int32_t>(rng() % w), static_cast<int32_t>(rng() % h)};
    const Cell t{static_cast<int32_t>(rng() % w), static_cast<int32_t>(rng() % h)};
    const PlanStatus st = astar.search(g, s, t, o, path);
    if (g.impassable(s, o.unknown)) {
      EXPECT_EQ(st, PlanStatus::StartBlocked);
      continue;
    }
    if (g.impassable(t, o.unknown)) {
      EXPECT_EQ(st, PlanStatus::GoalBlocked);
      continue;
    }
    const double ref = dijkstra(g, s, t, o);
    if (std::isinf(ref)) {
      EXPECT_EQ(st, PlanStatus::NoPath) << "trial " << trial;
      EXPECT_TRUE(path.empty());
      continue;
    }
    ASSERT_EQ(st, PlanStatus::Ok) << "trial " << trial;
    EXPECT_NEAR(astar.last_cost(), ref, 1e-3) << "trial " << trial;
    ASSERT_FALSE(path.empty());
    EXPECT_EQ(path.front(), s);
    EXPECT_EQ(path.back(), t);
    expect_valid_path(g, path, o);
    ++solved;
  }
  EXPECT_GT(solved, 100);
}

TEST(GridAstar, ReportsBlockedEndsAndNoPath) {
  const PlanningGrid g = test::grid_from_art({
      ".#..",
      ".#.i",
      ".#..",
  });
  GridAstar astar;
  std::vector<Cell> path;
  EXPECT_EQ(astar.search(g, {1, 0}, {0, 0}, {}, path), PlanStatus::StartBlocked);
  EXPECT_EQ(astar.search(g, {0, 0}, {3, 1}, {}, path), PlanStatus::GoalBlocked);
  EXPECT_EQ(astar.search(g, {0, 0}, {2, 2}, {}, path), PlanStatus::NoPath);
  EXPECT_EQ(astar.search(g, {0, 0}, {0, 2}, {}, path), PlanStatus::Ok);
  EXPECT_EQ(path.size(), 3u);
}

TEST(GridAstar, NeverCutsCorners) {
  // Diagonal (0,0)->(1,1) passes between two blocked cells: not allowed.
  const PlanningGrid g = test::grid_from_art({
      "x.",
      ".#",
  });
  GridAstar astar;
  std::vector<Cell> path;
  EXPECT_EQ(astar.search(g, {0, 0}, {1, 1}, {}, path), PlanStatus::NoPath);
}

TEST(GridAstar, UnknownPolicyBlocksOrCosts) {
  const PlanningGrid g = test::grid_from_art({
      ".......",
      "...?...",
      ".#####.",
  });
  GridAstar astar;
  std::vector<Cell> path;
  const Cell s{0, 1};
  const Cell t{6, 1};
  AstarOptions blocked{UnknownPolicy::Blocked, 1.0};
  ASSERT_EQ(astar.search(g, s, t, blocked, path), PlanStatus::Ok);
  EXPECT_NEAR(astar.last_cost(), 4.0 + 2.0 * std::sqrt(2.0), 1e-4);  // around the unknown cell
  AstarOptions cheap{UnknownPolicy::Allowed, 1.0};
  ASSERT_EQ(astar.search(g, s, t, cheap, path), PlanStatus::Ok);
  EXPECT_NEAR(astar.last_cost(), 6.0, 1e-4);  // straight through
  AstarOptions dear{UnknownPolicy::Allowed, 5.0};
  ASSERT_EQ(astar.search(g, s, t, dear, path), PlanStatus::Ok);
  EXPECT_NEAR(astar.last_cost(), 4.0 + 2.0 * std::sqrt(2.0), 1e-4);  // detour is cheaper again
  const PlanningGrid unknown_goal = test::grid_from_art({"..?"});
  EXPECT_EQ(astar.search(unknown_goal, {0, 0}, {2, 0}, blocked, path), PlanStatus::GoalBlocked);
  EXPECT_EQ(astar.search(unknown_goal, {0, 0}, {2, 0}, cheap, path), PlanStatus::Ok);
}

}  // namespace
}  // namespace slam::planner
