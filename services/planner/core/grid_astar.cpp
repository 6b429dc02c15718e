// The A* search loop and its radix-heap open list. Stale open entries are not removed: a node
// improved later gets a smaller key, is popped and closed first, and its old entries are skipped.
#include "planner/core/grid_astar.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace slam::planner {

namespace {

constexpr float kDiagonal = 1.41421356f;
// Neighbour offsets: four orthogonal (k = 0..3, counter-clockwise from +x), then four diagonals.
constexpr int32_t kDx[8] = {1, 0, -1, 0, 1, -1, -1, 1};
constexpr int32_t kDy[8] = {0, 1, 0, -1, 1, 1, -1, -1};

float octile(int32_t x, int32_t y, Cell goal) {
  const float dx = static_cast<float>(std::abs(x - goal.x));
  const float dy = static_cast<float>(std::abs(y - goal.y));
  return dx + dy + (kDiagonal - 2.0f) * std::min(dx, dy);
}

uint32_t key_of(float f) {
  return std::bit_cast<uint32_t>(f);
}

size_t bucket_of(uint32_t key, uint32_t last) {
  return key == last ? 0 : static_cast<size_t>(32 - std::countl_zero(key ^ last));
}

}  // namespace

void GridAstar::begin_query(size_t cells) {
  if (nodes_.size() != cells) {
    nodes_.assign(cells, Node{0.0f, 0});
    parent_dir_.assign(cells, 0);
    generation_ = 0;
  }
  if (generation_ >= (std::numeric_limits<uint32_t>::max() >> 1) - 1) {
    for (Node& n : nodes_) n.stamp = 0;
    generation_ = 0;
  }
  ++generation_;
  for (auto& b : buckets_) b.clear();
  open_size_ = 0;
  last_key_ = 0;
}

void GridAstar::push(float f, uint32_t index) {
  // Rounding can put a key a hair below the last popped one; the heap needs monotone keys.
  const uint32_t key = std::max(key_of(f), last_key_);
  buckets_[bucket_of(key, last_key_)].push_back(OpenEntry{key, index});
  ++open_size_;
}

uint32_t GridAstar::pop() {
  if (buckets_[0].empty()) {
    size_t i = 1;
    while (buckets_[i].empty()) ++i;
    auto& from = buckets_[i];
    uint32_t lowest = from[0].key;
    for (const OpenEntry& e : from) lowest = std::min(lowest, e.key);
    last_key_ = lowest;
    for (const OpenEntry& e : from) buckets_[bucket_of(e.key, last_key_)].push_back(e);
    from.clear();
  }
  const OpenEntry top = buckets_[0].back();
  buckets_[0].pop_back();
  --open_size_;
  return top.index;
}

PlanStatus GridAstar::search(const PlanningGrid& grid, Cell start, Cell goal, const AstarOptions& options,
                             std::vector<Cell>& out) {
  out.clear();
  last_cost_ = 0.0;
  last_expanded_ = 0;
  if (!grid.contains(start) || grid.impassable(start, options.unknown)) {
    return PlanStatus::StartBlocked;
  }
  if (!grid.contains(goal) || grid.impassable(goal, options.unknown)) {
    return PlanStatus::GoalBlocked;
  }
  begin_query(grid.cells().size());
  const uint32_t seen = generation_ * 2;
  const uint32_t closed = seen + 1;
  const bool allow_unknown = options.unknown == UnknownPolicy::Allowed;
  const float unknown_factor = static_cast<float>(std::max(1.0, options.unknown_cost_factor));
  const uint8_t* cells = grid.cells().data();
  const int32_t w = grid.width();
  const int32_t h = grid.height();
  // Step cost factor into a cell: 0 when it cannot be entered.
  auto entry_factor = [&](size_t i) -> float {
    const uint8_t c = cells[i];
    if (cell_blocked(c)) return 0.0f;
    if (cell_unknown(c)) return allow_unknown ? unknown_factor : 0.0f;
    return 1.0f;
  };

  const auto start_index = static_cast<uint32_t>(grid.index(start));
  const auto goal_index = static_cast<uint32_t>(grid.index(goal));
  nodes_[start_index] = Node{0.0f, seen};
  push(octile(start.x, start.y, goal), start_index);

  while (open_size_ > 0) {
    const uint32_t index = pop();
    Node& node = nodes_[index];
    if (node.stamp == closed) continue;
    node.stamp = closed;
    ++last_expanded_;
    if (index == goal_index) break;
    const int32_t y = static_cast<int32_t>(index / static_cast<uint32_t>(w));
    const int32_t x = static_cast<int32_t>(index - static_cast<uint32_t>(y * w));

    auto relax = [&](int k, float step) {
      const int32_t nx = x + kDx[k];
      const int32_t ny = y + kDy[k];
      const auto ni = static_cast<uint32_t>(ny * w + nx);
      Node& n = nodes_[ni];
      if (n.stamp == closed) return;
      const float g = node.g + step;
      if (n.stamp != seen || g < n.g) {
        n = Node{g, seen};
        parent_dir_[ni] = static_cast<uint8_t>(k);
        push(g + octile(nx, ny, goal), ni);
      }
    };
    // Orthogonal neighbours first: a diagonal needs both orthogonals it passes between.
    const bool inside[4] = {x + 1 < w, y + 1 < h, x > 0, y > 0};
    float factor[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int k = 0; k < 4; ++k) {
      if (!inside[k]) continue;
      factor[k] = entry_factor(static_cast<size_t>((y + kDy[k]) * w + x + kDx[k]));
      if (factor[k] > 0.0f) relax(k, factor[k]);
    }
    // Diagonal 4+k lies between orthogonals k and k+1.
    for (int k = 0; k < 4; ++k) {
      if (factor[k] == 0.0f || factor[(k + 1) & 3] == 0.0f) continue;
      const int d = 4 + k;
      const float f = entry_factor(static_cast<size_t>((y + kDy[d]) * w + x + kDx[d]));
      if (f > 0.0f) relax(d, kDiagonal * f);
    }
  }

  if (nodes_[goal_index].stamp != closed) return PlanStatus::NoPath;
  last_cost_ = nodes_[goal_index].g;
  Cell c = goal;
  out.push_back(c);
  while (!(c == start)) {
    const uint8_t k = parent_dir_[grid.index(c)];
    c = Cell{c.x - kDx[k], c.y - kDy[k]};
    out.push_back(c);
  }
  std::reverse(out.begin(), out.end());
  return PlanStatus::Ok;
}

}  // namespace slam::planner
