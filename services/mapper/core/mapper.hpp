#pragma once
// The mapper's logic without transport: owns the grid and the store, integrates observations, answers
// requests (layout, edits, map files), keeps the keyframe corrections, runs rebuilds and re-renders on
// a worker and numbers what the loop publishes.
// The DDS edge (MapperNode) feeds it plain requests and observations and sends what it returns.
//
// Rebuilds (layout change, robot reset, import, re-render after new corrections) run on a worker with its own
// store connection. A re-render redraws only the tiles of the keyframes that moved (partial_rerender.hpp,
// mapper_rerender.cpp), found through the FootprintIndex the mapper keeps of every stored observation;
// when that cannot be exact or would cost more, it rebuilds the whole grid. While one runs, observations are
// integrated into the current grid and kept aside (not yet stored, so the rebuild sees exactly what was
// committed when it started); when the new grid is ready they are integrated into it and stored, and it is
// swapped in. Requests arriving meanwhile wait and run afterwards, in order. Not thread-safe: one loop thread
// calls everything.
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/result.hpp"
#include "mapper/core/corrections.hpp"
#include "mapper/core/footprint_index.hpp"
#include "mapper/core/mapper_options.hpp"
#include "mapper/core/observation_store.hpp"
#include "mapper/core/occupancy_grid.hpp"
#include "mapper/core/rebuild_worker.hpp"
#include "mapper/core/robot_footprints.hpp"

namespace slam::mapper {

// A request's outcome (map.idl's MapResult).
enum class RequestResult { Ok, InvalidRequest, IoError, BadFile, UnknownRobot };
// The reply's result for a failure's code (MapError); a failure without one is an invalid request.
RequestResult failure_result(ErrorCode code);

struct RequestReply {
  uint64_t request_id = 0;
  RequestResult result = RequestResult::Ok;
  std::string message;
};

// A new grid layout (map.idl's GridConfig request). width_m/height_m 0 and a negative
// inflation_radius keep the current values (what slamctl sends for "unchanged").
struct LayoutRequest {
  uint64_t request_id = 0;
  double resolution = 0.0;
  double origin_x = 0.0;
  double origin_y = 0.0;
  double width_m = 0.0;
  double height_m = 0.0;
  double inflation_radius = -1.0;
  bool legacy_mode = false;
};

// Values as map.idl's MapEditKind; others are answered "unknown edit kind".
enum class EditKind : int32_t { Obstruct, Unobstruct, ClearObstructions, ResetRobot };
struct EditRequest {
  uint64_t request_id = 0;
  EditKind kind = EditKind::Obstruct;
  Vec2 point;
  std::string robot_id;  // ResetRobot
};

// Values as map.idl's MapFileAction; others are answered "unknown action".
enum class FileAction : int32_t { Export, Import, ExportTrajectoryTum, ExportTrajectoryCarmen };
struct FileRequest {
  uint64_t request_id = 0;
  FileAction action = FileAction::Export;
  std::string yaml_path;      // the map's YAML, or the trajectory's text file
  std::string robot_id = {};  // ExportTrajectory*: whose trajectory
};

using MapCommand = std::variant<LayoutRequest, EditRequest, FileRequest>;

// `current` with the fields a layout request sets, validated (the error names the key).
Result<GridConfig> requested_config(const LayoutRequest& request, const GridConfig& current);

// One robot observation as it arrived: raw, in the robot's odometry frame.
struct RobotScan {
  std::string_view robot_id;
  uint64_t seq = 0;
  int64_t stamp_ns = 0;
  ObservationView view;        // odometry frame
  KeyframeId keyframe_id = 0;  // stored with it; a re-render moves it by this keyframe's correction
  Pose map_from_odom;          // the robot's correction now: where it lands in the live grid
  int64_t robot_stamp_ns = 0;  // when it was measured, on the robot's own clock; 0: the robot sent none
};

// One observation that owns its points (the views of RobotScan and ObservationRecord live only as
// long as their source): what waits for its keyframe in the correction stage, what a replay reads.
struct OwnedObservation {
  std::string robot_id;
  uint64_t seq = 0;
  int64_t stamp_ns = 0;
  int64_t robot_stamp_ns = 0;  // 0: the robot sent none
  double x = 0, y = 0, theta = 0;
  bool has_heading = false;
  std::vector<Vec2> hits, misses;

  // Copies an observation in, reusing this record's string and point buffers.
  void assign(std::string_view robot, uint64_t sequence, int64_t stamp, const ObservationView& obs,
              int64_t robot_stamp = 0) {
    robot_id.assign(robot);
    seq = sequence;
    stamp_ns = stamp;
    robot_stamp_ns = robot_stamp;
    x = obs.x;
    y = obs.y;
    theta = obs.theta;
    has_heading = obs.has_heading;
    hits.assign(obs.hits.begin(), obs.hits.end());
    misses.assign(obs.misses.begin(), obs.misses.end());
  }
  ObservationView view() const { return {x, y, theta, has_heading, hits, misses}; }
};

// How a change set is numbered on the wire: the layout it belongs to and its version.
struct PublishStamp {
  uint32_t layout_id = 0;
  uint64_t version = 0;
};

class Mapper {
 public:
  // Opens the store and rebuilds the grid from it (errors name the store's path). `on_rebuild_done`
  // runs on the worker thread when a rebuild finishes (to wake the loop); keep it short.
  // `first_layout_id` numbers the first published layout (a restarted mapper's ids must differ).
  static Result<std::unique_ptr<Mapper>> create(const MapperOptions& options, Counters& counters,
                                                uint32_t first_layout_id,
                                                std::function<void()> on_rebuild_done);
  ~Mapper();  // lands a running rebuild, commits the store
  Mapper(const Mapper&) = delete;
  Mapper& operator=(const Mapper&) = delete;

  // Integrates one observation, moved into the map frame by scan.map_from_odom, and stores it raw with
  // its keyframe id (kept aside while a rebuild runs). now_ns: monotonic time, for the other-robot
  // filter.
  void integrate(const RobotScan& scan, int64_t now_ns);
  // Counts and logs an observation refused before it reached the grid.
  void reject(std::string_view robot_id, uint64_t seq, const std::string& reason);

  // Stores keyframes (inserted or replaced by id, in the open batch: save a keyframe before the
  // observations that reference it) and takes their corrections for later re-renders.
  Status save_keyframes(std::span<const Keyframe> keyframes);
  // Re-renders the grid from the store with the current keyframe corrections (same layout), now or
  // after the running rebuild; several requests while one waits make one re-render. No reply: the
  // swap publishes a snapshot.
  void rerender();
  const KeyframeCorrections& corrections() const { return corrections_; }
  // Where every stored observation is drawn, per keyframe (what a re-render plans with).
  const FootprintIndex& footprints() const { return index_; }
  // Every stored keyframe (to restore the pose graph at start-up).
  Result<std::vector<Keyframe>> load_keyframes() { return store_->keyframes(); }

  // Runs `command` now, or after the running rebuild; replies land in take_replies().
  void submit(MapCommand command);
  // Lands a finished rebuild (swaps the grid, stores the observations kept aside, replies) and runs
  // the requests that waited for it. Call every loop pass.
  void poll_rebuild();
  // mapper_compaction.cpp. Starts a compaction on the worker when one is due (compaction.hpp): at
  // most every --store-compact-interval-s, while nothing else runs or waits. poll_rebuild() calls it.
  void maybe_compact();
  // Starts one now if the plan finds rows to compact (tests, benches); true when started.
  bool compact_now();
  // Blocks until a running rebuild finishes and lands it (shutdown, tests).
  void wait_for_rebuild();
  bool rebuilding() const { return worker_.busy(); }
  // Commits the store's open batch (not while a rebuild runs: nothing is appended then).
  void commit();

  // Replies due since the last call, in order.
  std::vector<RequestReply> take_replies();

  // Publication. At a patch tick the grid's dirty tiles are the changes; when needs_snapshot() the
  // layout changed and a patch cannot describe it.
  bool needs_snapshot() const { return grid_->layout_version() != seen_layout_; }
  PublishStamp next_patch() const { return {layout_id_, version_ + 1}; }
  void patch_sent() {
    grid_->clear_dirty();
    ++version_;
  }
  // Numbers a snapshot and takes every change into it; `new_version` when it replaces changes no
  // patch carried (after a rebuild, a grown grid or a failed patch).
  PublishStamp prepare_snapshot(bool new_version);
  // True once after a rebuild swapped the grid in: publish a snapshot with a new version now.
  bool take_swapped();

  const OccupancyGrid& grid() const { return *grid_; }
  // Whether the grid holds a loaded map (a prior imported into the store).
  bool has_prior() const { return has_prior_; }
  // Whether the grid holds any wall (observed occupied or obstructed): a map to localise on.
  bool has_walls() const;
  const MapperOptions& options() const { return options_; }

 private:
  struct Metrics {
    explicit Metrics(Counters& c);
    std::atomic<int64_t>& observations;
    std::atomic<int64_t>& points;
    std::atomic<int64_t>& rejected;
    std::atomic<int64_t>& rebuilds;
    std::atomic<int64_t>& requests;
    std::atomic<int64_t>& request_errors;
    std::atomic<int64_t>& store_observations;
    std::atomic<int64_t>& store_errors;
    std::atomic<int64_t>& robot_hits_filtered;
    std::atomic<int64_t>& rerenders_partial;       // re-renders that redrew only what moved
    std::atomic<int64_t>& rerender_observations;   // observations replayed by re-renders (partial or full)
    std::atomic<int64_t>& compactions;             // compactions landed
    std::atomic<int64_t>& compacted_observations;  // raw rows they replaced by the baseline
  };

  // An observation integrated while a rebuild runs, kept (raw) for the new grid and the store.
  struct Deferred {
    std::string robot_id;
    uint64_t seq = 0;
    int64_t stamp_ns = 0;
    int64_t robot_stamp_ns = 0;
    KeyframeId keyframe_id = 0;
    Pose map_from_odom;  // what it was integrated with, unless its keyframe has a correction by then
    double x = 0, y = 0, theta = 0;
    bool has_heading = false;
    std::vector<Vec2> hits;
    std::vector<Vec2> misses;
    ObservationView view() const;
  };

  enum class RebuildCause { Layout, ResetRobot, Import, Rerender, PartialRerender, Compaction };
  // Who waits for the running rebuild, and what to do when it lands.
  struct RebuildTicket {
    RebuildCause cause = RebuildCause::Layout;
    uint64_t request_id = 0;
    GridConfig config;
    std::string done;                        // reply text on success (the rebuild's figures are appended)
    std::optional<MapImage> previous_prior;  // Import: restored if the rebuild fails
  };

  Mapper(const MapperOptions& options, Counters& counters, uint32_t first_layout_id,
         std::function<void()> on_rebuild_done);
  Status open();

  // Stores it raw and records in the index where it is drawn (`drawn`: its correction, `box`: map frame).
  void store_observation(std::string_view robot, uint64_t seq, int64_t stamp_ns, KeyframeId keyframe_id,
                         const ObservationView& odom, int64_t robot_stamp_ns, const Pose& drawn,
                         const MapBox& box);
  // Stores the observations kept aside during a rebuild that did not replace the grid: they are drawn
  // where the live grid drew them.
  void store_deferred_as_drawn();
  void handle(const MapCommand& command);
  void handle_layout(const LayoutRequest& request);
  void handle_edit(const EditRequest& edit);
  void handle_file(const FileRequest& request);
  void start_rebuild(RebuildTicket ticket);
  void finish_rebuild(RebuildOutcome outcome);
  // mapper_rerender.cpp: a partial re-render when the plan allows one (`full`: a full one regardless).
  void start_rerender(bool full);
  void finish_partial(RebuildOutcome outcome);
  // mapper_compaction.cpp.
  bool start_compaction(bool due_only);
  void finish_compaction(RebuildOutcome outcome);
  void run_queued_commands();
  void reply(uint64_t request_id, RequestResult result, const std::string& message);

  MapperOptions options_;
  Metrics metrics_;
  RateLimitedLog log_;

  std::optional<ObservationStore> store_;
  std::optional<OccupancyGrid> grid_;
  uint32_t layout_id_ = 0;    // published; changes when size, origin or resolution change
  uint32_t seen_layout_ = 0;  // grid_->layout_version() last published
  uint64_t version_ = 0;      // last published change set (patch, or grid-replacing snapshot)
  bool swapped_ = false;      // a rebuild replaced the grid; not yet published
  KeyframeCorrections corrections_;
  FootprintIndex index_;
  int64_t newest_stamp_ns_ = 0;      // the newest stored gateway stamp: the clock compaction ages by
  int64_t last_full_redraw_ns_ = 0;  // newest_stamp_ns_ when a full re-render last moved everything
  bool has_prior_ = false;           // the store holds a prior
  int64_t loop_now_ns_ = 0;          // the last integrate()'s monotonic time
  int64_t next_compaction_check_ns_ = 0;
  bool rerender_waiting_ = false;       // a re-render requested while a rebuild ran
  bool full_rerender_waiting_ = false;  // ... and it must be a full one (a partial one could not be exact)
  std::vector<Vec2> odom_hits_;         // the observation being integrated, odometry frame
  std::vector<Vec2> odom_misses_;
  std::vector<Vec2> hits_;  // the same, map frame
  std::vector<Vec2> misses_;
  RobotFootprints footprints_;
  std::vector<Deferred> deferred_;       // observations integrated during a rebuild
  std::optional<RebuildTicket> ticket_;  // the running rebuild's
  std::deque<MapCommand> queued_;        // requests waiting for the rebuild
  std::vector<RequestReply> replies_;
  RebuildWorker worker_;
};

}  // namespace slam::mapper
