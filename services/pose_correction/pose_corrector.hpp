#pragma once
// The SLAM core's front door: one per mapper. Keeps, per robot, the correction map <- odom that
// turns what the robot reports (its own drifting odometry frame) into the map frame.
//
// Flow, driven by the mapper's loop thread (not thread-safe; the optimiser has its own thread, and
// with match_threads = 1 the matching runs on a MatchWorker, see match_worker.hpp):
//  1. add() each raw observation: it joins its robot's open keyframe (KeyframeBuilder). The mapper
//     holds the observation, unrendered, until that keyframe is finalised: matching a keyframe
//     against a map that already holds its own points would only confirm the prediction.
//  2. process() matches every closed keyframe against the grid near its predicted pose (narrow
//     window), adds it to the pose graph (a sequential edge to the robot's previous keyframe, an
//     edge to the old keyframes it matched against) and, when the robot is back among keyframes
//     made long ago (by itself or another robot) but the narrow match fails, tries a loop closure:
//     a wide-window match against a grid drawn from those old keyframes only, accepted only when
//     it agrees with the odometry uncertainty accumulated since the robot was last tied to the old
//     map (ConsistencyCheck). Finalised keyframes come back with their correction. How much of the
//     work around tracking (ties, wide searches) runs depends on the backlog (CorrectionSchedule);
//     each pass starts at most a budget of keyframes. With a worker, a keyframe's result lands at a
//     later process(); a robot has at most one keyframe in matching, so its keyframes stay in order.
//  3. Accepted closures (and every so many tied keyframes) start a background optimisation; when
//     it lands, take_optimised() hands over every keyframe whose correction moved, so the mapper
//     re-renders the grid from its store and persists them.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"
#include "pose_correction/branch_and_bound_search.hpp"
#include "pose_correction/clock_steps.hpp"
#include "pose_correction/correction_schedule.hpp"
#include "pose_correction/free_space_check.hpp"
#include "pose_correction/grid_view.hpp"
#include "pose_correction/keyframe_builder.hpp"
#include "pose_correction/keyframe_index.hpp"
#include "pose_correction/match_worker.hpp"
#include "pose_correction/odometry_calibration.hpp"
#include "pose_correction/odometry_trust.hpp"
#include "pose_correction/pose_graph.hpp"
#include "pose_correction/scan_matcher.hpp"
#include "pose_correction/wall_axes.hpp"

namespace slam::correction {

class GraphOptimizer;

enum class CorrectionSource : uint8_t { Identity, Match, Loop, Operator, Restored };

struct CorrectorOptions {
  KeyframeOptions keyframe;
  MatcherOptions matcher;
  SearchWindow track_window{0.15, 0.08};  // every keyframe, around the prediction
  SearchWindow closure_window{1.0, 0.3};  // loop closure, around the prediction
  double closure_min_score = 0.6;         // mean likelihood a closure match must reach
  double old_age_s = 60.0;                // a keyframe this old (or another robot's) counts as "old map"
  double closure_radius_m = 2.0;          // old keyframes this close to the prediction are candidates
  int closure_min_keyframes = 4;          // fewer old keyframes around: no closure attempt
  // A tracking match's covariance is the search response's spread times this. The spread is
  // deliberately broad (MatcherOptions::independent_points keeps a ridge visible to the closure
  // gate), which overstates a distinct match's error: at 1 tracking followed odometry through new
  // rooms and drifted twice as far (replayed runs, docs/mapping-quality.md).
  double track_variance_scale = 0.5;
  // The same for a keyframe of laser scans (KeyframeOptions::scan_points), read with this many
  // independent points: a scan pins its pose far better than the odometry of a 10 cm step, and
  // fusing it at the sparse robots' weight left real robots' headings to drift (the benchmark logs,
  // docs/mapping-quality.md).
  double scan_track_variance_scale = 0.05;
  double scan_independent_points = 100.0;
  // A keyframe of scans spans a few degrees of turning, over which real odometry can be off by as
  // much again (Freiburg 079's by 5-10 degrees a second): its heading is searched wider.
  SearchWindow scan_track_window{0.15, 0.2};
  // A scan keyframe whose tracking match lies on its window's edge (odometry off by more than the
  // window: Freiburg 079's odometry integrates forward while the robot backs up at 0.5 m/s) is
  // searched again by branch and bound in this wider window, and the tracking window's match around
  // what it finds is taken when it is no longer on the edge and scores better.
  SearchWindow scan_recovery_window{0.6, 0.4};
  double scan_recovery_gain = 0.05;  // ...by at least this much more mean likelihood (0..1)
  // What makes a loop closure's match distinct. A scan's hundreds of points put a second peak that
  // sums nine tenths of the best far below it (its weight under the response's reading is e^-8 at
  // 700 points), where a sparse keyframe's would still be a real rival.
  DistinctMatch distinct;
  DistinctMatch scan_distinct{0.95, 0.05, 0.035};
  double odom_sigma_m_per_sqrt_m = 0.03;  // odometry edge noise (a little above the usual drift)
  double odom_sigma_rad_per_m = 0.02;     // heading noise per metre travelled (edge and chain)
  // The walls' heading (wall_axes.hpp): each keyframe's heading is pulled toward the one its
  // straight walls give against the map's axes, and held there in the graph. It acts only once the
  // map's walls agree on two perpendicular directions, so maps with walls at many angles are left
  // alone; off for a building whose walls are square to each other only in places.
  bool wall_heading = true;
  // Each robot's systematic odometry heading error (odometry_calibration.hpp) learned from its
  // matches and taken out of its odometry; off for robots whose odometry is calibrated already.
  bool odometry_calibration = true;
  WallAxisOptions wall_axis;
  double wall_heading_floor_rad = 0.005;  // added to a reading's spread: no building is exactly square
  double wall_heading_gate_rad = 0.08;    // a larger correction is not taken: a wall at another angle
  // Each match (tracking and tie) refined against the points of the keyframes around it
  // (point_refiner.hpp): the grid alone leaves walls up to half a cell off.
  bool point_refine = true;
  // The keyframes around a match: those within its farthest point, at most local_reach_m, hold the
  // points a tie's local grid and the point refinement read; at most tie_max_keyframes old ones
  // (nearest first) for a tie, refine_max_keyframes for the refinement.
  double local_reach_m = 10.0;
  size_t tie_max_keyframes = 40;
  size_t refine_max_keyframes = 60;
  double window_margin_m = 0.3;  // beyond a keyframe's farthest point: the matcher's field blur
  double tied_sigma_m = 0.05;    // chain uncertainty above which a tie searches the wide window
  // After a long loop a sparse robot can be metres off, beyond closure_window, where one keyframe's
  // few dozen points fit many places. While its chain's sigma
  // exceeds relocalise_sigma_m, the points of its last placement_trail_m of keyframes are searched by branch
  // and bound within 3 sigma (at most relocalise_max_m, relocalise_max_rad) among the old keyframes there,
  // and a match as distinct as a placement's is taken as a loop closure once relocalise_confirmations
  // keyframes in a row agree on it (as global localisation confirms a placement).
  // Off by default (the mapper's --slam-relocalise): a robot just switched on beside others' keyframes
  // has a loose chain too, and in the simulator's two-room world such a search took the other room.
  bool relocalise = false;
  double relocalise_sigma_m = 0.5;
  double relocalise_max_m = 8.0;
  double relocalise_max_rad = 0.6;
  int relocalise_confirmations = 3;
  // A trail whose rays run through more than this share of the old keyframes' walls is a look-alike
  // place. The trail is drawn at its drifting estimates and a 16-beam keyframe's points were seen
  // from along its half metre, so true matches on the benchmark logs cross far more than a
  // placement's; the simulator's look-alike rooms were taken at 0.7 (0.3 refused most true ones).
  double relocalise_max_crossed_walls = 0.7;
  // A keyframe whose robot moved less than this since its previous one, and within it, was taken
  // standing still: it sees what its previous keyframe saw, and matching it again adds nothing but
  // the chance to be dragged by other robots' fresh keyframes (placed by odometry instead).
  double standing_travel_m = 0.02;
  double standing_turn_rad = 0.02;
  // A robot whose odometry starts farther than this from the map's origin (a real robot's counters
  // start wherever they were last reset: the MIT CSAIL log's at x = 600 m) starts with its first pose
  // moved to the origin, heading kept, instead of beyond the map's extent.
  double far_start_m = 100.0;
  // A robot that joins a map others have built is first searched for on it (global localisation,
  // branch_and_bound_search.hpp over the whole map and every heading). Until it is placed its
  // keyframes wait, unmatched and unfinalised, so nothing of it is drawn into the shared map; it is
  // placed when placement_confirmations keyframes in a row agree on where its odometry frame lies,
  // each match distinct (runner-up at most placement_max_ambiguity of the best) and scoring at least
  // placement_min_score. A robot not found within placement_max_keyframes or placement_max_wait_s
  // is placed where its odometry says, as a robot on an empty map is. Off by default (the mapper's
  // --slam-global-localisation): until an unplaced robot maps into a submap of its own, waiting
  // delays a robot's share of the map by its first few metres.
  bool global_localisation = false;
  int placement_confirmations = 3;
  double placement_min_score = 0.6;
  double placement_max_ambiguity = 0.85;
  double placement_agree_m = 0.3;  // a later keyframe's match this close to the hypothesis agrees
  double placement_agree_rad = 0.1;
  int placement_max_keyframes = 40;
  double placement_max_wait_s = 30.0;
  // What is searched: the newest keyframe and the ones before it within this much travel, by
  // odometry (a sparse robot's single keyframe fits many places), evenly thinned to max_points.
  double placement_trail_m = 4.0;
  // The whole map is searched again only once the robot has moved this far since the last search:
  // the keyframes in between add little to a 4 m trail, and each whole-map search costs tens of
  // milliseconds (confirming a hypothesis searches only around it, every keyframe).
  double placement_search_travel_m = 0.5;
  size_t placement_max_points = 400;
  // A match whose rays run through more than this share of the map's walls is a look-alike place
  // (free_space_check.hpp), however well its points land. True placements of the benchmark logs'
  // robots cross 10-18 % (a few metres of real odometry smear the trail; 30 m rays pass doorways
  // and glass), look-alikes in the simulator's office about 40 %.
  double placement_max_crossed_walls = 0.3;
  size_t placement_max_map_cells = 1 << 20;  // a larger map is searched at a coarser resolution
  int optimise_every = 40;                   // keyframes tied to the old map between optimisations
  double rerender_shift_m = 0.02;            // keyframe moves smaller than this are not re-rendered
  ScheduleOptions schedule;
  int match_threads = 0;  // 0: match inside process() (deterministic: tests, offline); 1: on a worker
};

// A keyframe whose correction is final (for now: a later optimisation may move it again).
struct KeyframeCorrection {
  uint64_t id = 0;
  std::string robot;
  uint32_t segment = 0;
  Pose odom;        // keyframe origin in the robot's odometry frame
  Pose correction;  // map_from_odom for every observation of the keyframe
};

// Whether the robot's place in the map is known: searched for (Unplaced: no hypothesis yet; Placing:
// a hypothesis, being confirmed) or Placed (by its start on an empty map, by the search, by an
// operator, or by its odometry after the search gave up).
enum class Placement : uint8_t { Placed, Placing, Unplaced };

struct RobotCorrection {
  std::string robot;
  Placement placement = Placement::Placed;
  double localisation_score = 1.0;  // the latest placement search's: score x (1 - ambiguity), 0..1
  Pose map_from_odom;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // how well it is known in the map (correction.idl)
  uint64_t version = 0;
  uint32_t segment = 0;
  uint32_t keyframes = 0;
  uint32_t loop_closures = 0;
  CorrectionSource source = CorrectionSource::Identity;
};

struct CorrectorStats {
  int64_t keyframes = 0;
  int64_t matched = 0;    // narrow matches accepted
  int64_t unmatched = 0;  // keyframes placed by odometry alone (too few points, poor score)
  int64_t standing = 0;   // keyframes of a robot standing still: placed by odometry, not matched
  int64_t closures_tried = 0;
  int64_t closures_accepted = 0;
  int64_t closures_rejected = 0;  // a match was found but failed the consistency check
  int64_t optimisations = 0;
  int64_t failed_optimisations = 0;
  int64_t segments = 0;         // odometry jumps that started a new segment
  int64_t rejected_inputs = 0;  // non-finite observations, bad initial poses
  int64_t clock_steps = 0;      // stamps or process() times set back by more than 10 s (clock_steps.hpp)
  int64_t wall_headings = 0;    // keyframes whose heading the walls corrected
  int64_t point_refined = 0;    // matched keyframes refined against the points of the keyframes around
  // Scheduling under load (CorrectionSchedule).
  int64_t ties_tried = 0;          // keyframes matched against old keyframes (narrow or wide)
  int64_t ties_skipped = 0;        // near old map, but the load allowed no tie
  int64_t wide_skipped = 0;        // a wide search was needed but rate-limited
  int64_t placed_by_odometry = 0;  // backlog overflow: finalised without any matching
  int64_t backlog = 0;             // keyframes closed and not yet finalised (now)
  int64_t open_messages = 0;       // observations in the robots' open keyframes (now)
  int64_t load = 0;                // the schedule's load now: 0 normal, 1 loaded, 2 shedding
  int64_t robots_reset = 0;
  // Global localisation (CorrectorOptions::global_localisation).
  int64_t placement_searches = 0;
  int64_t robots_placed = 0;           // found on the map
  int64_t placements_given_up = 0;     // not found: placed by their odometry
  int64_t placement_contradicted = 0;  // a hypothesis a later keyframe disagreed with
};

// How one keyframe was placed, for diagnostics (eval_replay --trace-keyframes compares each pose
// with the truth): which of prediction, match and map agreed tells a tracking error from a map
// built in the wrong place.
struct KeyframeDecision {
  std::string_view robot;
  int64_t stamp_ns = 0;       // the keyframe's first observation
  Pose odom;                  // its origin in the robot's odometry frame
  Pose predicted;             // the robot's correction before it, applied to `odom`
  std::optional<Pose> match;  // the tracking match (none: too few points, a poor score)
  Eigen::Matrix3d match_covariance = Eigen::Matrix3d::Zero();
  std::optional<double> wall_heading;  // the heading its walls gave against the map's axes, when taken
  Pose estimate;                       // where it was placed: fused, then tied or closed
  bool tied = false;                   // to old keyframes (a narrow tie or an accepted closure)
  bool closure = false;
  // The robot's uncertainty after it, as the corrector holds it to check a loop closure: grown by
  // odometry since the robot was last tied to the old map, shrunk by each tie; a new trajectory
  // segment, the robot's first included, starts barely known (2 m).
  Eigen::Matrix3d uncertainty = Eigen::Matrix3d::Zero();
};

class PoseCorrector {
 public:
  explicit PoseCorrector(const CorrectorOptions& options = {});
  ~PoseCorrector();
  PoseCorrector(const PoseCorrector&) = delete;
  PoseCorrector& operator=(const PoseCorrector&) = delete;

  // A raw observation (pose and hits in the robot's odometry frame), `stamp_ns` on the clock
  // process() is given (arrival), `robot_stamp_ns` the robot's own when it sent one (it groups
  // keyframes). Returns the id of the keyframe it belongs to. Non-finite values: an error, nothing
  // changed, counted.
  Result<uint64_t> add(std::string_view robot, int64_t stamp_ns, const Pose& odom_pose, bool has_heading,
                       std::span<const Vec2> hits, std::optional<int64_t> robot_stamp_ns = std::nullopt);

  // Closes keyframes of robots silent since max_span, applies the matches that landed, starts
  // matching closed keyframes against `grid` (up to the pass budget) and appends the finalised ones
  // to `out` (in order per robot). Inline (match_threads 0) a keyframe closed before the call is
  // finalised by it unless the budget ran out.
  void process(const GridView& grid, int64_t now_ns, std::vector<KeyframeCorrection>& out);

  // When a background optimisation has landed: appends the keyframes whose correction moved to
  // `moved` and returns the largest move in metres (0 when nothing landed).
  double take_optimised(std::vector<KeyframeCorrection>& moved);

  // Closes every robot's open keyframe and has the next process() optimise the whole graph, whatever
  // the load: what a finished run (a played log, a trajectory export) needs for its final poses.
  void finish();

  // An operator's initial pose: the robot is at `map_pose` now (for robots without heading,
  // map_pose.theta is the rotation of its odometry frame). Errors: unknown robot, non-finite.
  Status set_initial_pose(std::string_view robot, const Pose& map_pose);

  // After a restart: keyframes as stored (their corrections become each robot's current one).
  void restore(std::span<const KeyframeCorrection> keyframes);

  // An operator's robot reset (its observations are deleted): its keyframes leave the pose graph,
  // the keyframe index and matching; its open and waiting keyframes are dropped. Its current
  // correction stays (the robot still is where it was believed to be); its next keyframe starts a
  // new chain. Returns how many finalised keyframes were removed; an unknown robot: 0.
  size_t reset_robot(std::string_view robot);
  // Keyframes in the pose graph (removed ones not counted).
  size_t graph_keyframes() const { return nodes_.size() - removed_nodes_; }

  // The robot's current correction; identity for an unknown robot.
  Pose correction(std::string_view robot) const;
  // Whether the robot has sent an observation (an initial pose needs one to anchor to).
  bool knows(std::string_view robot) const;
  // Robots whose correction changed since the last call.
  void take_changed(std::vector<RobotCorrection>& out);
  const CorrectorStats& stats() const { return stats_; }
  // Whether a background optimisation is running or waiting to be taken.
  bool optimising() const { return optimising_; }
  // Blocks until the background optimisation has finished (take it with the next process() or
  // take_optimised()): for offline replays that must not depend on the solver's timing.
  void wait_for_optimisation() const;
  // Called with every keyframe as it is placed (on the caller's thread, inside process()); the
  // decision's `robot` is valid during the call only.
  void set_keyframe_observer(std::function<void(const KeyframeDecision&)> observer) {
    keyframe_observer_ = std::move(observer);
  }

 private:
  struct Robot {
    Robot(std::string robot, const KeyframeOptions& options) : name(std::move(robot)), builder(options) {}
    std::string name;
    KeyframeBuilder builder;
    RobotCorrection state;
    Eigen::Matrix3d chain_cov = Eigen::Matrix3d::Zero();  // uncertainty since last tied to old map
    // How well it is known in the map: chain_cov, except that a trusted start (its first keyframe)
    // is known well rather than at a new segment's 2 m. Published with its correction.
    Eigen::Matrix3d pose_cov = Eigen::Matrix3d::Zero();
    // Of its heading in the map: grown by odometry, shrunk by the walls' heading and by ties. Unlike
    // chain_cov it starts small at the robot's trusted start.
    double heading_variance = 0.0;
    // Its next keyframes' headings are given (its trusted start, an operator's pose): those whose
    // walls are clear anchor the map's axes (MapWallAxes). How many are left.
    int anchors_walls = 0;
    OdometryTrust odometry_trust;              // scales its odometry covariance
    OdometryCalibration odometry_calibration;  // its odometry's systematic heading error
    std::optional<uint32_t> last_node;         // slot of its previous keyframe
    std::vector<uint32_t> recent_nodes;        // slots of its latest keyframes, oldest first (its trail)
    // While its chain is loose: where its odometry frame lies by the trail's search, and how many
    // keyframes in a row agreed.
    std::optional<Pose> relocalise_hypothesis;
    int relocalise_agreed = 0;
    std::optional<uint32_t> last_tied;  // slot of its last keyframe tied to the map
    std::optional<Pose> operator_pose;  // correction set by an operator, for its next keyframe
    bool has_heading = false;           // of its latest observation
    bool changed = false;
    CorrectionSchedule::RobotState schedule;
    uint32_t generation = 0;  // bumped by a reset: its keyframes in matching are dropped
    bool matching = false;    // a keyframe of it is on the worker
    // While it is searched for on the map: its closed keyframes, waiting; the correction its
    // keyframes' matches agree on so far, and how many agreed.
    std::vector<Keyframe> held;
    std::optional<Pose> hypothesis;
    int confirmations = 0;
    std::optional<Vec2> searched_at;  // odometry position of the keyframe last searched for
  };
  // One pose-graph node per finalised keyframe.
  struct Node {
    uint64_t id = 0;
    uint32_t robot = 0;
    uint32_t segment = 0;
    int64_t stamp_ns = 0;
    Pose odom;
    Pose estimate;             // map pose of the keyframe origin
    std::vector<Vec2> points;  // keyframe frame; empty for restored keyframes
    bool fixed = false;
    bool removed = false;  // its robot was reset: kept as a tombstone so slots stay valid
  };

  // Keyframes after a trusted start that may anchor the map's wall axes: odometry barely drifts
  // over the first few.
  static constexpr int kAnchoringKeyframes = 3;
  // A correction moving a robot this far (by a keyframe or an optimisation) is logged as a warning.
  static constexpr double kJumpWarning_m = 0.3;
  // A robot's latest keyframes kept for its trail: 4 m at a sparse robot's 0.4 m keyframes, with
  // room for turns on the spot.
  static constexpr size_t kRecentNodes = 32;
  // A ray's last stretch may pass a wall seen a little off without counting as a crossing: the
  // search's lattice (a cell, a heading step) and walls a cell or two thick.
  static constexpr double kWallCrossingMargin_m = 0.3;
  // The old keyframes' grid a loose robot is searched on: coarser than the map, since it spans metres
  // of uncertainty and only has to find the place for the tracking matcher to refine.
  static constexpr double kRelocaliseResolution_m = 0.1;
  // The observations' stamps or process()'s clock going back further than this were set back: the
  // step is taken out (ClockSteps).
  static constexpr int64_t kClockStepBack_ns = 10'000'000'000;
  static constexpr int64_t kPlacementMapAge_ns = 10'000'000'000;

  uint32_t robot_index(std::string_view robot);
  // Global localisation (pose_corrector_placement.cpp): a robot's newest held keyframe searched for
  // on `grid`; placed once enough agree, or by its odometry once it has waited too long.
  void search_placement(Robot& rb, const GridView& grid, int64_t now_ns);
  // Places the robot by its odometry when it has waited too long (keyframes or time); whether it did.
  bool give_up_placement(Robot& rb, int64_t now_ns);
  void prepare_placement_map(const GridView& grid);
  void place(Robot& rb, std::optional<Pose> map_from_odom, double score);
  // `t_ns` on `clock` with its steps back taken out; a step is counted and logged as `what`'s.
  int64_t take_out_clock_steps(ClockSteps& clock, int64_t t_ns, std::string_view what);
  // A closed keyframe: prepared on the loop thread, matched (inline or on the worker), applied on
  // the loop thread. match = false: placed by odometry alone.
  void start(Keyframe&& keyframe, const GridView& grid, bool match, std::vector<KeyframeCorrection>& out);
  void prepare(Keyframe&& keyframe, const GridView& grid, bool match, MatchJob& job);
  // The matching itself: reads and writes only `job` (and the options), so it may run on the worker.
  void match_keyframe(ScanMatcher& matcher, MatchJob& job) const;
  // A scan keyframe's tracking match off its window's edge, searched again wider (scan_recovery_window).
  void recover_track(ScanMatcher& matcher, const GridView& view, MatchJob& job,
                     Result<MatchResult>& narrow) const;
  // A matched keyframe into the graph and its robot's correction (pose_corrector_apply.cpp), by the
  // steps below.
  void apply(MatchJob& job, std::vector<KeyframeCorrection>& out);
  // What apply() decided about the old keyframes the job matched against.
  struct TieDecision {
    std::optional<uint32_t> anchor;  // slot of the old keyframe it is tied to; none: no tie
    Pose estimate;                   // where the tie puts the keyframe
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    bool closure = false;  // a wide match that moved the keyframe: a loop closure, bends the chain
  };
  // An optimisation that landed while the job was matched moved the robot's correction from the
  // one the job was prepared with to `correction`: moves the job's poses with it.
  void carry_into_correction(MatchJob& job, const Pose& correction) const;
  // Counts the tracking match (or its absence) and teaches the robot's odometry trust from it.
  // Returns the robot's correction source after it.
  CorrectionSource learn_from_tracking(const MatchJob& job, Robot& rb);
  // Whether the tie match is taken, and as a loop closure (counted and logged).
  TieDecision decide_tie(const MatchJob& job, const Robot& rb, bool operator_set);
  // The trail's match (relocalise_sigma_m), once relocalise_confirmations keyframes in a row agree
  // on it, becomes `tie`: a loop closure.
  void confirm_relocalisation(const MatchJob& job, Robot& rb, TieDecision& tie);
  // Moves `estimate` by the tie (fused) or closure (taken, the chain bent), and the robot's
  // uncertainty with it. Returns the new estimate.
  Pose apply_tie(const Keyframe& keyframe, Robot& rb, const TieDecision& tie, const Pose& estimate);
  // An operator's pose for the robot's next keyframe: the estimate it gives, the robot known as well.
  Pose apply_operator_pose(const MatchJob& job, Robot& rb);
  // The keyframe's node (its points moved out of the job) and its edges: sequential, tie, walls'
  // heading, prior. Returns its slot.
  uint32_t add_node_and_edges(MatchJob& job, const Robot& rb, const Pose& estimate,
                              const Pose& tracked_motion, const TieDecision& tie, bool operator_set);
  // The keyframe's walls into the map's axes (anchoring them at the robot's first keyframes).
  void learn_wall_axes(const MatchJob& job, Robot& rb, const Pose& estimate);
  // The robot's correction and published state moved to the keyframe; the keyframe appended to `out`.
  void publish_keyframe(const MatchJob& job, Robot& rb, const Pose& estimate, CorrectionSource source,
                        const TieDecision& tie, std::vector<KeyframeCorrection>& out);
  // Applies the jobs the worker finished.
  void land(std::vector<KeyframeCorrection>& out);
  std::unique_ptr<MatchJob> take_job();
  void recycle(std::unique_ptr<MatchJob> job);
  // Old keyframes (another robot's, or older than old_age_s) near `centre`, nearest first.
  void old_neighbours(uint32_t robot, int64_t stamp_ns, Vec2 centre, double radius,
                      std::vector<uint32_t>& out);
  // A loose sparse robot's search among the old keyframes around it (relocalise_sigma_m), planned.
  void prepare_relocalisation(const Robot& rb, const Keyframe& keyframe, MatchJob& job);
  // The rays of the robot's keyframes over placement_trail_m before `keyframe` (same segment) and
  // its own, in the frame of `keyframe` placed at `pose`, evenly thinned to placement_max_points.
  void gather_recent_trail(const Robot& rb, const Keyframe& keyframe, const Pose& pose,
                           std::vector<Ray>& out);
  // The search itself (on the worker): the trail over the region, refined by the tracking matcher.
  void search_relocalisation(ScanMatcher& matcher, MatchJob& job) const;
  // The points (map frame) within the square of half_extent around `centre` of the keyframes within
  // `reach` of it (the nearest ones): what a match there is refined against.
  void window_points(Vec2 centre, double reach, double half_extent, std::vector<Vec2>& out);
  // The points of `slots` (map frame, at their current estimates) within the square of half_extent.
  void gather_points(std::span<const uint32_t> slots, Vec2 centre, double half_extent,
                     std::vector<Vec2>& out) const;
  // Draws the points of `slots` (at their current estimates) into `cells` around `centre`.
  GridGeometry draw_local_grid(std::span<const uint32_t> slots, Vec2 centre, double half_extent,
                               double resolution, std::vector<uint8_t>& cells) const;
  Eigen::Matrix3d odometry_covariance(const Pose& relative) const;
  void add_edge(EdgeKind kind, uint32_t from, uint32_t to, const Pose& measurement,
                const Eigen::Matrix3d& cov);
  // A loop closure moves the robot's keyframe from `from` to `to`: bends its untied recent chain.
  void bend_chain(uint32_t robot, uint32_t segment, const Pose& from, const Pose& to);
  void start_optimisation();
  void rebuild_index();
  void mark_changed(Robot& robot, CorrectionSource source);

  CorrectorOptions options_;
  ScanMatcher matcher_;
  std::vector<Robot> robots_;
  std::unordered_map<std::string, uint32_t> robot_ids_;
  std::vector<Keyframe> closed_;
  std::vector<Node> nodes_;
  std::vector<GraphEdge> edges_;  // `from`/`to` are keyframe ids
  KeyframeIndex index_;
  MapWallAxes wall_axes_;
  uint64_t next_id_ = 1;
  int tied_since_optimise_ = 0;
  bool closure_since_optimise_ = false;
  bool finish_requested_ = false;  // finish(): optimise at the next process()
  bool optimising_ = false;
  uint64_t epoch_ = 0;            // bumped when keyframes move outside the optimiser (closures, operator)
  uint64_t submitted_epoch_ = 0;  // epoch_ when the running optimisation was submitted
  std::vector<KeyframeCorrection> pending_moved_;  // bent by closures, not yet taken
  double pending_shift_ = 0.0;
  std::unique_ptr<GraphOptimizer> optimizer_;
  std::vector<Pose> submitted_estimates_;  // node estimates when the running optimisation started
  // The map global localisation searches: built from the live grid when a search needs it and
  // the last build is older than kPlacementMapAge_ns.
  BranchAndBoundSearch placement_search_;
  int64_t placement_map_ns_ = 0;
  bool placement_map_ready_ = false;
  std::vector<uint8_t> placement_cells_;  // scratch: the grid's occupied part, maybe coarsened
  std::vector<Ray> placement_trail_;      // scratch: the searched keyframes' rays
  std::vector<Ray> placement_rays_;       // scratch: ...thinned
  std::vector<Vec2> placement_points_;    // scratch: ...their ends
  std::vector<uint32_t> searching_;       // scratch: robots with a keyframe held in this pass
  int64_t last_process_ns_ = 0;           // now_ns of the latest process()
  int64_t submitted_ns_ = 0;              // ...when the running optimisation started
  size_t submitted_nodes_ = 0;
  // add()'s stamps and process()'s now_ns, their steps back taken out.
  ClockSteps stamp_clock_{kClockStepBack_ns};
  ClockSteps process_clock_{kClockStepBack_ns};
  std::function<void(const KeyframeDecision&)> keyframe_observer_;
  CorrectorStats stats_;
  size_t removed_nodes_ = 0;
  CorrectionSchedule schedule_;
  std::unique_ptr<MatchWorker> worker_;  // null: inline matching
  size_t in_flight_ = 0;                 // jobs on the worker
  // Reused buffers.
  std::vector<uint32_t> neighbours_;
  std::vector<std::unique_ptr<MatchJob>> spare_jobs_;
  std::vector<std::unique_ptr<MatchJob>> landed_;
};

}  // namespace slam::correction
