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
#include <algorithm>
#include <cmath>
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
#include "pose_correction/corrector_options.hpp"
#include "pose_correction/free_space_check.hpp"
#include "pose_correction/grid_view.hpp"
#include "pose_correction/job_thread.hpp"
#include "pose_correction/keyframe_builder.hpp"
#include "pose_correction/keyframe_index.hpp"
#include "pose_correction/match_worker.hpp"
#include "pose_correction/odometry_calibration.hpp"
#include "pose_correction/odometry_direction.hpp"
#include "pose_correction/odometry_trust.hpp"
#include "pose_correction/placement_search.hpp"
#include "pose_correction/pose_graph.hpp"
#include "pose_correction/scan_matcher.hpp"
#include "pose_correction/wall_axes.hpp"

namespace slam::correction {

class GraphOptimizer;

enum class CorrectionSource : uint8_t { Identity, Match, Loop, Operator, Restored };

// A keyframe whose correction is final (for now: a later optimisation may move it again).
struct KeyframeCorrection {
  uint64_t id = 0;
  std::string robot;
  uint32_t segment = 0;
  Pose odom;        // keyframe origin in the robot's odometry frame
  Pose correction;  // map_from_odom for every observation of the keyframe
  // An unplaced or lost robot's keyframe dropped while it was searched for: where it was is unknown,
  // so its observations are dropped, not drawn.
  bool discarded = false;
};

// Whether the robot's place in the map is known: searched for (Unplaced: no hypothesis yet; Placing:
// a hypothesis, being confirmed; Lost: it was placed, then its keyframes stopped fitting the map
// where it was thought to be) or Placed (by its start on an empty map, by the search, by an
// operator, or by its odometry after the search gave up).
enum class Placement : uint8_t { Placed, Placing, Unplaced, Lost };

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
  int64_t robots_placed = 0;               // found on the map
  int64_t placement_contradicted = 0;      // a hypothesis a later keyframe disagreed with
  int64_t placements_refused = 0;          // matches at a place an operator rejected
  int64_t robots_lost = 0;                 // placed robots whose keyframes stopped fitting the map
  int64_t unplaced_keyframes_dropped = 0;  // of unplaced and lost robots: older than the latest waiting
  // A loose sparse robot searched for by its trail (CorrectorOptions::relocalise).
  int64_t trail_searches = 0;
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

  // An operator's answer to where the robot is being placed. Accept: a robot being confirmed
  // (Placing) is placed where its hypothesis puts it. Reject: that place is refused for the robot
  // from now on (until an operator's pose or a reset), and it is searched for elsewhere; a placed
  // robot is searched for again as a lost one is. Errors (nothing changed, counted): unknown robot,
  // nothing to accept (no hypothesis yet) or to reject (not placed or being placed).
  Status answer_placement(std::string_view robot, bool accept);

  // After a restart: keyframes as stored (their corrections become each robot's current one).
  void restore(std::span<const KeyframeCorrection> keyframes);

  // An operator's robot reset (its observations are deleted): its keyframes leave the pose graph,
  // the keyframe index and matching; its open and waiting keyframes are dropped. Its current
  // correction stays (the robot still is where it was believed to be); its next keyframe starts a
  // new chain. Returns how many finalised keyframes were removed; an unknown robot: 0.
  size_t reset_robot(std::string_view robot);
  // Called on a worker thread when a match or placement search is done, so the caller's loop runs
  // process() again at once (match_threads > 0). Set it before the first process().
  void set_wake(std::function<void()> wake) { wake_ = std::move(wake); }
  // The map holds walls no robot drew here (a map loaded, or a restored store the graph does not
  // hold): with global localisation, a robot joining it is searched for, the first one too.
  void set_map_given(bool given) { map_given_ = given; }
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
    OdometryDirection odometry_direction;      // its odometry counting backward driving as forward
    std::optional<uint32_t> last_node;         // slot of its previous keyframe
    // Odometry pose of its last keyframe not taken standing: a keyframe is standing only within
    // the standing limits of it, so a slow turn in keyframes of one scan each is not one.
    std::optional<Pose> last_moving_odom;
    std::vector<uint32_t> recent_nodes;  // slots of its latest keyframes, oldest first (its trail)
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
    std::optional<Vec2> searched_at;   // odometry position of the keyframe last searched for
    int64_t searched_ns = 0;           // process()'s time of that search
    int searches_unfound = 0;          // whole-map searches in a row that found nothing distinct
    uint64_t looked_at = 0;            // id of the newest held keyframe its search last looked at
    int unmatched_in_row = 0;          // its latest keyframes whose tracking match failed
    std::vector<double> track_scores;  // its latest tracking matches' scores (a ring, lost_window long)
    size_t track_score_next = 0;       // ...where the next one goes
    bool lost = false;                 // searched for since it was lost
    std::vector<Pose> rejected;        // odometry frames an operator said it is not in (answer_placement)
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
  // The old keyframes' grid a loose robot is searched on: coarser than the map, since it spans metres
  // of uncertainty and only has to find the place for the tracking matcher to refine.
  static constexpr double kRelocaliseResolution_m = 0.1;
  // The observations' stamps or process()'s clock going back further than this were set back: the
  // step is taken out (ClockSteps).
  static constexpr int64_t kClockStepBack_ns = 10'000'000'000;
  static constexpr int64_t kPlacementMapAge_ns = 10'000'000'000;
  // A robot not found is searched for again once the map it was searched on is this old (doubled by
  // each search in a row that found nothing, up to 8 times), moved or not: the others map on, and one
  // standing where they have not been yet is found when they come.
  bool search_again(const Robot& rb, int64_t now_ns) const {
    return !rb.hypothesis && rb.searched_at &&
           now_ns - rb.searched_ns > (kPlacementMapAge_ns << std::min(rb.searches_unfound, 3));
  }
  // The travel before the next whole-map search: placement_search_travel_m, doubled by each search in
  // a row that found nothing, up to the trail searched (a robot driving where nothing is mapped, or
  // among look-alikes, is not searched for every half metre of a long drive: each search costs a
  // tenth of a second to seconds).
  double search_travel_m(const Robot& rb) const {
    return std::min(options_.placement_trail_m,
                    std::ldexp(options_.placement_search_travel_m, std::min(rb.searches_unfound, 16)));
  }

  uint32_t robot_index(std::string_view robot);
  // Global localisation (pose_corrector_placement.cpp): each robot searched for whose newest held
  // keyframe has not been looked at, in turns (inline all of them; on the placement thread one at a
  // time, the next pass starting with the robot that waited).
  void search_placements(const GridView& grid, int64_t now_ns);
  // A robot's newest held keyframe searched for on `grid`; placed once enough agree.
  void search_placement(uint32_t robot, const GridView& grid, int64_t now_ns);
  // Applies the placement search the thread finished, if any.
  void land_placement();
  // A search's outcome for its robot: a hypothesis made, confirmed or dropped; placed once enough agree.
  void apply_placement(const PlacementJob& job);
  // Whether an operator rejected a frame that puts the keyframe at `odom` where `frame` does.
  bool rejected(const Robot& rb, const Pose& frame, const Pose& odom) const;
  // A placed robot whose latest keyframes do not fit the map where it is thought to be: its chain
  // ends there and it is searched for on the whole map, drawing nothing meanwhile.
  void mark_lost(Robot& rb, const std::string& why);
  void watch_tracking(const MatchJob& job, Robot& rb);
  // Places the robot by its odometry when it has waited too long (keyframes or time); whether it did.
  // An unplaced robot keeps only its latest placement_max_keyframes waiting (the others: `out`, discarded).
  void trim_held(Robot& rb, std::vector<KeyframeCorrection>& out);
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
  // Localising only: the keyframe replaces its robot's latest node (no points, no edges, not indexed:
  // nothing is tied to it or optimised); its slot.
  uint32_t keep_latest_node(const MatchJob& job, const Robot& rb, const Pose& estimate);
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
  // Global localisation's search and the map it searches, rebuilt from a copy of the live grid when
  // a search needs it and the last one is older than kPlacementMapAge_ns. With match_threads, the
  // searcher belongs to the placement thread (one search at a time, off the loop).
  std::function<void()> wake_;  // set_wake(); before the threads that call it (they end first)
  PlacementSearcher placement_searcher_;
  std::unique_ptr<JobThread<PlacementJob>> placement_thread_;  // null: inline searches
  bool placement_in_flight_ = false;
  std::unique_ptr<PlacementJob> placement_job_;  // reused: its buffers keep their capacity
  std::vector<std::unique_ptr<PlacementJob>> landed_placements_;
  int64_t placement_map_ns_ = 0;
  bool placement_map_ready_ = false;
  bool map_given_ = false;       // set_map_given()
  uint32_t placement_turn_ = 0;  // the robot whose search waits for the thread
  int64_t last_process_ns_ = 0;  // now_ns of the latest process()
  int64_t submitted_ns_ = 0;     // ...when the running optimisation started
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
