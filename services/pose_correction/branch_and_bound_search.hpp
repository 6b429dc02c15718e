#pragma once
// A search over a whole map (or a wide region of it) for where a keyframe's points fit best: x, y and
// every heading, exactly as a brute-force correlative search would score them on the likelihood field,
// found by branch and bound (as Cartographer's global constraint search). The map is prepared once:
// its likelihood field and, per level d, the maximum of the field over every 2^d x 2^d block of
// cells. A node of the search is a heading and a 2^d x 2^d block of translations; its score, read
// from level d, bounds every translation in the block, so blocks that cannot beat the best leaf so
// far are never opened.
//
// The second-best candidate at least `distinct_separation_m` away from the best is searched too: a
// match that a look-alike place (an identical room, a corridor's other end) scores almost as well is
// a guess, and a wrong placement is worse than none.
#include <cstdint>
#include <span>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"
#include "pose_correction/grid_view.hpp"
#include "pose_correction/likelihood_field.hpp"

namespace slam::correction {

struct BranchAndBoundOptions {
  double field_sigma_m = 0.05;  // blur of the likelihood field, as the local matcher's
  // Levels of the precomputation: a top node spans 2^depth cells (64 cells: 3.2 m at 5 cm).
  int depth = 6;
  // Points farther than this from the keyframe's origin are not used: they set the heading step
  // (one cell at the farthest point), and a global search over thousands of headings must stay fast.
  double max_point_range_m = 12.0;
  int min_points = 20;
  double min_score = 0.5;  // mean likelihood (0..1) of the points at the best pose
  // Another candidate this far from the best (metres, heading counted as the arc it swings at the
  // points' RMS range) belongs to another place; the best such gives `runner_up_score`.
  double distinct_separation_m = 0.5;
  // The runner-up is only searched down to this share of the best score: below it the match is not
  // ambiguous, whatever it is exactly.
  double runner_up_floor = 0.7;
  size_t max_map_cells = size_t{1} << 24;  // over all levels: a larger map is refused, not searched slowly
};

struct SearchRegion {
  Pose centre;                  // the region's middle and the heading the angular range is around
  double linear_m = 1.0;        // +- in x and y
  double angular_rad = 3.1416;  // +-; pi or more: every heading
};

struct GlobalMatch {
  Pose pose;                     // on the search's lattice (whole cells, the heading step)
  double score = 0.0;            // mean likelihood of the points there, 0..1
  double runner_up_score = 0.0;  // the best candidate distinct from it (0 when none above the floor)
  double ambiguity() const { return score > 0.0 ? runner_up_score / score : 0.0; }
  uint64_t nodes_scored = 0;  // work done, for benchmarks and logs
};

class BranchAndBoundSearch {
 public:
  explicit BranchAndBoundSearch(const BranchAndBoundOptions& options = {});

  // Prepares the search over `grid` (its likelihood field and the levels). The view is copied into
  // the levels; it need not outlive this call.
  Status set_map(const GridView& grid);
  bool has_map() const { return !levels_.empty(); }
  const BranchAndBoundOptions& options() const { return options_; }
  const GridGeometry& geometry() const { return geometry_; }

  // `points` in the keyframe's own frame. Errors: no map, too few points, a region off the map, or
  // no candidate scoring min_score.
  Result<GlobalMatch> search(std::span<const Vec2> points, const SearchRegion& region);

 private:
  struct Candidate {
    int32_t heading = 0;   // index into headings_
    int32_t x = 0, y = 0;  // translation of the block's lower corner, cells from the region's centre
    int32_t depth = 0;
    float score = 0.0f;  // summed bound over the points
  };
  // A best leaf, and the one to stay away from while searching the runner-up.
  struct Leaf {
    Candidate candidate;
    bool found = false;
  };

  void prepare_headings(std::span<const Vec2> points, const SearchRegion& region);
  float bound(const Candidate& c) const;
  double separation(const Candidate& a, const Candidate& b) const;
  void branch(const Candidate& node, float& threshold, Leaf& best, const Leaf* exclude);
  Pose pose_of(const Candidate& c) const;

  BranchAndBoundOptions options_;
  GridGeometry geometry_;
  int32_t margin_ = 0;  // cells of zeros around the map in every level
  int32_t level_width_ = 0, level_height_ = 0;
  std::vector<std::vector<float>> levels_;  // [d]: max of the field over [x, x+2^d) x [y, y+2^d)
  LikelihoodField field_;

  // Per search, reused: the points' cells at each heading (relative to the region's centre cell).
  std::vector<Vec2> points_;      // the points used (within max_point_range_m)
  std::vector<double> headings_;  // absolute headings searched
  std::vector<Cell> rotated_;     // [heading][point]: the point's level cell, no translation
  int32_t reach_cells_ = 0;       // +- translations, cells
  double rms_range_ = 1.0;
  std::vector<Candidate> top_;  // the top-level nodes, best first
  uint64_t nodes_scored_ = 0;
};

}  // namespace slam::correction
