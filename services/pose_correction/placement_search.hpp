#pragma once
// Global localisation's search as a unit of work that can leave the mapper's loop (PlacementJob),
// and what runs it (PlacementSearcher): the map it searches, the live grid's occupied part coarsened
// to a budget, and a branch-and-bound search over it (branch_and_bound_search.hpp). A whole-map
// search takes about 0.1 s on an office (docs/performance.md): on the loop it would stall the
// tracking of every placed robot, so the mapper runs it on a JobThread of its own, one at a time.
//
// Threading as match_worker.hpp: a job carries copies of what its search reads (the trail's rays,
// and, when the searched map is due to be rebuilt, the live grid's classes); the searcher is touched
// only by the thread that runs it.
#include <cstdint>
#include <optional>
#include <vector>

#include "common/core/geometry.hpp"
#include "pose_correction/branch_and_bound_search.hpp"
#include "pose_correction/corrector_options.hpp"
#include "pose_correction/free_space_check.hpp"
#include "pose_correction/grid_view.hpp"

namespace slam::correction {

struct PlacementJob {
  // Filled on the loop thread.
  uint32_t robot = 0;
  uint32_t generation = 0;  // the robot's (a reset drops the job)
  Pose keyframe_odom;       // the newest held keyframe's origin, in the robot's odometry frame
  // Where the robot's odometry frame lies if the last search was right: the keyframe is searched
  // for around where that puts it. None: on the whole map at every heading.
  std::optional<Pose> hypothesis;
  std::vector<Ray> rays;  // the trail, in the newest keyframe's frame (each from its keyframe's origin)
  bool new_map = false;   // the searched map is rebuilt from the grid below first
  GridGeometry grid_geometry;
  std::vector<uint8_t> grid_cells;
  // Filled by the search.
  bool map_ready = false;  // the searched map holds walls (else nothing was searched)
  std::optional<GlobalMatch> found;
  // The match passed every test: its score, its distinctness (a whole-map search), and at most
  // placement_max_crossed_walls of its rays through the map's walls.
  bool passes = false;
};

class PlacementSearcher {
 public:
  explicit PlacementSearcher(const CorrectorOptions& options);
  void run(PlacementJob& job);

 private:
  // One searched map: the grid's occupied part with a margin, coarsened until it fits a budget.
  struct SearchedMap {
    explicit SearchedMap(const BranchAndBoundOptions& options) : search(options) {}
    BranchAndBoundSearch search;
    std::vector<uint8_t> cells;
    bool ready = false;
  };
  static void set_map(const GridView& grid, size_t max_cells, SearchedMap& map);

  CorrectorOptions options_;
  SearchedMap whole_;         // placement_whole_map_cells: the whole map at every heading
  SearchedMap around_;        // placement_max_map_cells: around a hypothesis
  std::vector<Vec2> points_;  // scratch: the rays' ends
};

}  // namespace slam::correction
