#pragma once
// The matching around one keyframe, as a unit of work that can leave the mapper's loop thread, and
// the thread that runs such units.
//
// Threading: a MatchJob carries copies of everything its matching reads (the keyframe's points, a
// window of the live grid around the prediction, the local grid of old keyframes), made on the loop
// thread before submit(). The worker reads and writes only the job until it hands it back, so
// neither the mapper's grid (which the loop keeps writing) nor the pose graph is ever shared: copies
// rather than a lock, because a window is small (a 10 x 10 m box at 5 cm: 40 kB, microseconds to
// copy) while a lock on the grid would stall integration for a whole match (job_thread.hpp).
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "common/core/geometry.hpp"
#include "pose_correction/branch_and_bound_search.hpp"
#include "pose_correction/free_space_check.hpp"
#include "pose_correction/job_thread.hpp"
#include "pose_correction/keyframe_builder.hpp"
#include "pose_correction/point_refiner.hpp"
#include "pose_correction/scan_matcher.hpp"
#include "pose_correction/wall_axes.hpp"

namespace slam::correction {

struct MatchJob {
  // Filled on the loop thread.
  Keyframe keyframe;
  uint32_t generation = 0;           // the robot's generation (a reset drops jobs of earlier ones)
  Pose prepared_correction;          // the robot's map_from_odom when the job was prepared
  Pose predicted;                    // keyframe origin in the map
  std::optional<uint32_t> previous;  // slot of the robot's previous keyframe (same segment)
  Pose odom_motion;                  // from the previous keyframe, as the odometry reported it
  Pose odom_relative;  // ...with the robot's learned odometry error taken out (OdometryCalibration)
  Eigen::Matrix3d odom_cov = Eigen::Matrix3d::Zero();
  // The robot stood still since its previous keyframe: placed by odometry, nothing matched.
  bool standing = false;
  bool track = false;  // match against the live grid's window
  GridGeometry track_geometry;
  std::vector<uint8_t> track_cells;
  std::vector<Vec2> track_points;  // the points of the keyframes around it (map frame) in that window
  bool tie = false;                // match against the old keyframes around it
  bool wide_needed = false;        // the robot's chain is loose: the tie must search the wide window
  bool wide_permitted = false;
  uint32_t anchor = 0;  // slot of the nearest old keyframe
  size_t neighbours = 0;
  GridGeometry tie_geometry;
  std::vector<uint8_t> tie_cells;
  std::vector<Vec2> tie_points;  // the old keyframes' points that tie_cells were drawn from
  // A sparse robot whose chain is loose is searched for among the old keyframes around it
  // (CorrectorOptions::relocalise_sigma_m): its recent trail (keyframe frame) over `relocalise_region`
  // on a grid drawn from them.
  bool relocalise = false;
  bool relocalise_confirming = false;  // around the hypothesis: the runner-up is not asked about
  uint32_t relocalise_anchor = 0;      // slot of the old keyframe nearest the region's centre
  SearchRegion relocalise_region;
  GridGeometry relocalise_geometry;
  std::vector<uint8_t> relocalise_cells;
  std::vector<Ray> relocalise_rays;
  std::vector<Vec2> relocalise_points;  // ...their ends
  std::optional<double> map_axis;       // the map's wall axes (MapWallAxes), when known
  // Of the robot's heading in the map: its previous keyframe's, then (by the matching) with this
  // keyframe's motion added and the walls' heading taken.
  double heading_variance = 0.0;
  // Filled by the matching.
  std::optional<MatchResult> narrow;
  Pose tracked;   // the prediction, fused with the narrow match when there is one
  Pose estimate;  // `tracked`, its heading pulled toward the walls' when they gave one
  std::optional<WallAxisReading> wall_reading;
  std::optional<double> wall_heading;    // the heading the walls gave, when it was taken
  double wall_variance = 0.0;            // ...and its variance
  WallAxisReader wall_reader;            // scratch
  PointRefiner refiner;                  // scratch
  BranchAndBoundSearch recovery_search;  // scratch: a tracking match off its window's edge
  std::vector<uint8_t> recovery_cells;   // scratch: the part of the track grid it searches
  bool point_refined = false;            // the narrow match was refined against track_points
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  bool wide = false;          // the tie searched the wide window
  bool wide_skipped = false;  // a wide search was needed but not permitted
  std::optional<MatchResult> tie_match;
  std::optional<MatchResult> relocalised;  // the trail's match, refined on the lattice's best
};

// One thread running jobs in submission order with its own ScanMatcher.
class MatchWorker {
 public:
  using Work = std::function<void(ScanMatcher&, MatchJob&)>;
  MatchWorker(const MatcherOptions& options, Work work, std::function<void()> on_done = {})
      : matcher_(options),
        work_(std::move(work)),
        thread_([this](MatchJob& job) { work_(matcher_, job); }, std::move(on_done)) {}

  void submit(std::unique_ptr<MatchJob> job) { thread_.submit(std::move(job)); }
  // Appends the finished jobs, in submission order.
  void take_done(std::vector<std::unique_ptr<MatchJob>>& out) { thread_.take_done(out); }

 private:
  ScanMatcher matcher_;
  Work work_;
  JobThread<MatchJob> thread_;  // last: its thread uses the matcher
};

}  // namespace slam::correction
