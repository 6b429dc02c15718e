#include "pose_correction/placement_search.hpp"

#include <algorithm>
#include <numbers>

#include "common/core/cell_class.hpp"

namespace slam::correction {
namespace {

// The occupied part of `grid` (cells of a wall or an obstruction), with a margin: what a keyframe
// can be placed against. Empty when nothing is occupied.
CellBox occupied_box(const GridView& grid, int32_t margin) {
  const GridGeometry& g = grid.geometry;
  int32_t x0 = g.width, y0 = g.height, x1 = -1, y1 = -1;
  for (int32_t y = 0; y < g.height; ++y) {
    const uint8_t* row = grid.classes.data() + static_cast<size_t>(y) * static_cast<size_t>(g.width);
    for (int32_t x = 0; x < g.width; ++x) {
      if (!is_wall(row[x])) continue;
      x0 = std::min(x0, x);
      x1 = std::max(x1, x);
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
    }
  }
  if (x1 < 0) return {};
  x0 = std::max(0, x0 - margin);
  y0 = std::max(0, y0 - margin);
  x1 = std::min(g.width - 1, x1 + margin);
  y1 = std::min(g.height - 1, y1 + margin);
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

}  // namespace

// A look-alike matters only when it scores within placement_max_ambiguity of the best: the search for
// the runner-up stops there instead of ranking every weaker place (on a large map most of its cost).
PlacementSearcher::PlacementSearcher(const CorrectorOptions& options)
    : options_(options),
      whole_(BranchAndBoundOptions{.runner_up_floor = options.placement_max_ambiguity}),
      around_(BranchAndBoundOptions{.runner_up_floor = options.placement_max_ambiguity}) {}

void PlacementSearcher::set_map(const GridView& grid, size_t max_cells, SearchedMap& map) {
  map.ready = false;
  const GridGeometry& g = grid.geometry;
  if (g.cells() == 0 || grid.classes.size() != g.cells()) return;
  const CellBox box = occupied_box(grid, 4);
  if (box.empty()) return;
  // Coarser cells (each the occupancy of a square of grid cells) until the map fits the budget.
  int32_t factor = 1;
  while (box.cells() / static_cast<size_t>(factor * factor) > max_cells) factor *= 2;
  GridGeometry coarse;
  coarse.resolution = g.resolution * factor;
  coarse.origin = g.corner({box.x0, box.y0});
  coarse.width = (box.width + factor - 1) / factor;
  coarse.height = (box.height + factor - 1) / factor;
  map.cells.assign(coarse.cells(), kCellFree);
  for (int32_t y = 0; y < box.height; ++y) {
    const uint8_t* row = grid.classes.data() + g.index({box.x0, box.y0 + y});
    for (int32_t x = 0; x < box.width; ++x)
      if (is_wall(row[x])) map.cells[coarse.index({x / factor, y / factor})] = kCellOccupied;
  }
  map.ready = static_cast<bool>(map.search.set_map(GridView{coarse, map.cells}));
}

void PlacementSearcher::run(PlacementJob& job) {
  if (job.new_map) {
    const GridView grid{job.grid_geometry, job.grid_cells};
    set_map(grid, options_.placement_whole_map_cells, whole_);
    set_map(grid, options_.placement_max_map_cells, around_);
  }
  job.map_ready = whole_.ready && around_.ready;
  job.found.reset();
  job.passes = false;
  if (!job.map_ready) return;
  points_.clear();
  for (const Ray& r : job.rays) points_.push_back(r.end);
  // No hypothesis: the whole map at every heading. A hypothesis: around where it puts this keyframe.
  SearchedMap& searched = job.hypothesis ? around_ : whole_;
  const GridGeometry& map = searched.search.geometry();
  SearchRegion region;
  if (job.hypothesis) {
    region = {job.hypothesis->compose(job.keyframe_odom), options_.placement_agree_m,
              options_.placement_agree_rad};
  } else {
    const double half_width = 0.5 * map.width * map.resolution,
                 half_height = 0.5 * map.height * map.resolution;
    region = {{map.origin.x + half_width, map.origin.y + half_height, 0.0},
              std::max(half_width, half_height),
              2.0 * std::numbers::pi};
  }
  auto found = searched.search.search(points_, region);
  if (!found) return;
  job.found = *found;
  // The walls are traced only for a match that passes the cheaper tests.
  job.passes = found->score >= options_.placement_min_score &&
               (job.hypothesis || found->ambiguity() <= options_.placement_max_ambiguity) &&
               crossed_wall_share(GridView{map, searched.cells}, found->pose, job.rays,
                                  kWallCrossingMargin_m) <= options_.placement_max_crossed_walls;
}

}  // namespace slam::correction
