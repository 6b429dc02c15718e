#pragma once
// Frontier cells (free, not blocked, with an unknown 4-neighbour) kept up to date per grid patch,
// and their 8-connected clusters: where exploration sends robots next.
#include <cstdint>
#include <vector>

#include "planner/core/plan_types.hpp"
#include "planner/core/planning_grid.hpp"

namespace slam::planner {

struct FrontierCluster {
  uint32_t size = 0;  // frontier cells: the information gain estimate
  Vec2 centroid;      // mean of the cells' centres (may lie off the frontier)
  Cell target;        // the cluster's cell nearest the centroid: where a robot is sent
};

class FrontierMap {
 public:
  // Recomputes every cell.
  void rebuild(const PlanningGrid& grid);
  // Recomputes the cells whose frontier status a change inside `box` can affect (the box grown
  // by one cell). Falls back to rebuild() when the grid size changed.
  void update(const PlanningGrid& grid, const CellBox& box);

  // False until rebuilt for this grid's size: flags must not be read against another layout.
  bool matches(const PlanningGrid& grid) const {
    return flags_.size() == grid.cells().size() && width_ == grid.geometry().width;
  }
  bool is_frontier(Cell c, const PlanningGrid& grid) const { return flags_[grid.index(c)] != 0; }
  size_t count() const { return count_; }

  // 8-connected clusters of at least `min_cells` cells, in scan order, into `out`.
  void cluster(const PlanningGrid& grid, uint32_t min_cells, std::vector<FrontierCluster>& out);

 private:
  void recompute(const PlanningGrid& grid, int32_t x0, int32_t y0, int32_t x1, int32_t y1);

  std::vector<uint8_t> flags_;
  size_t count_ = 0;
  int32_t width_ = 0;
  int32_t height_ = 0;
  // Clustering scratch, reused between calls.
  std::vector<uint32_t> visited_;
  uint32_t visit_stamp_ = 0;
  std::vector<uint32_t> queue_;
};

}  // namespace slam::planner
