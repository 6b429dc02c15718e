#pragma once
// Grid A*: 8-connected, octile heuristic, no corner cutting past blocked cells. Buffers are sized
// once per grid size and reused: per-cell state is stamped with a query generation, so a query
// neither clears nor allocates after the first one on a grid of that size. The open list is a
// radix heap (vectors of entries, bucketed by key bits): with a consistent heuristic popped keys
// never decrease, which is what a radix heap needs, and it does far less work than a binary heap.
#include <array>
#include <cstdint>
#include <vector>

#include "planner/core/plan_types.hpp"
#include "planner/core/planning_grid.hpp"

namespace slam::planner {

struct AstarOptions {
  UnknownPolicy unknown = UnknownPolicy::Blocked;
  double unknown_cost_factor = 3.0;  // >= 1; step cost multiplier into unknown cells when allowed
};

class GridAstar {
 public:
  // Cheapest path from start to goal, cells in order start..goal into `out`. Returns Ok,
  // StartBlocked, GoalBlocked or NoPath (out is left empty unless Ok). Cells must be in the grid.
  PlanStatus search(const PlanningGrid& grid, Cell start, Cell goal, const AstarOptions& options,
                    std::vector<Cell>& out);

  // Cost of the last path found, in cell lengths (a straight step 1, a diagonal step sqrt 2).
  double last_cost() const { return last_cost_; }
  size_t last_expanded() const { return last_expanded_; }

 private:
  struct Node {
    float g;
    uint32_t stamp;  // 2*generation: seen this query; 2*generation+1: closed this query
  };
  struct OpenEntry {
    uint32_t key;  // the bits of a non-negative float f: they order like the floats
    uint32_t index;
  };

  void begin_query(size_t cells);
  void push(float f, uint32_t index);
  uint32_t pop();

  std::vector<Node> nodes_;
  std::vector<uint8_t> parent_dir_;  // direction (0..7) to the parent, valid where stamped
  std::array<std::vector<OpenEntry>, 33> buckets_;
  size_t open_size_ = 0;
  uint32_t last_key_ = 0;
  uint32_t generation_ = 0;
  double last_cost_ = 0.0;
  size_t last_expanded_ = 0;
};

}  // namespace slam::planner
