#pragma once
// slam-mapper's DDS edge: readers fill a locked intake; one loop thread drains it, owns the grid and
// the store, integrates observations, answers requests, and publishes patches at the patch rate and
// snapshots when the layout changes, after rebuilds and every snapshot period.
//
// Rebuilds (layout change, robot reset, import) run on a worker with its own store connection. While
// one runs, the loop keeps integrating observations into the current grid and keeps them aside
// (not yet stored, so the rebuild sees exactly what was committed when it started); when the new grid
// is ready they are integrated into it and stored, and it is swapped in. Requests arriving meanwhile
// wait and run afterwards, in order.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "mapper/mapper_intake.hpp"
#include "mapper/mapper_options.hpp"
#include "mapper/observation_store.hpp"
#include "mapper/occupancy_grid.hpp"
#include "mapper/rebuild_worker.hpp"

namespace slam::mapper {

class MapperNode {
 public:
  // Configure: store (rebuilds the grid from it), participant, writers, first snapshot, readers.
  // A failure undoes what was done; errors about the store name its path.
  static Result<std::unique_ptr<MapperNode>> create(const MapperOptions& options, Counters& counters);
  ~MapperNode();
  MapperNode(const MapperNode&) = delete;
  MapperNode& operator=(const MapperNode&) = delete;

  dds::Participant& participant() { return *participant_; }

  // One loop pass: waits until the next patch tick (less when a request arrives), applies what
  // arrived, and publishes what is due.
  void run_once();

 private:
  struct Metrics {
    explicit Metrics(Counters& c);
    std::atomic<int64_t>& observations;
    std::atomic<int64_t>& points;
    std::atomic<int64_t>& rejected;
    std::atomic<int64_t>& dropped;
    std::atomic<int64_t>& cells_changed;
    std::atomic<int64_t>& patches;
    std::atomic<int64_t>& snapshots;
    std::atomic<int64_t>& rebuilds;
    std::atomic<int64_t>& requests;
    std::atomic<int64_t>& request_errors;
    std::atomic<int64_t>& store_observations;
    std::atomic<int64_t>& store_bytes;
    std::atomic<int64_t>& store_errors;
    std::atomic<int64_t>& write_failures;
    std::atomic<int64_t>& robot_hits_filtered;
    std::atomic<int64_t>& observations_lost;  // DDS SAMPLE_LOST on the observation reader
  };

  // An observation integrated while a rebuild runs, kept for the new grid and the store.
  struct Deferred {
    std::string robot_id;
    uint64_t seq = 0;
    int64_t stamp_ns = 0;
    double x = 0, y = 0, theta = 0;
    bool has_heading = false;
    std::vector<Vec2> hits;
    std::vector<Vec2> misses;
    ObservationView view() const;
  };

  enum class RebuildCause { Layout, ResetRobot, Import };
  // Who waits for the running rebuild, and what to do when it lands.
  struct RebuildTicket {
    RebuildCause cause = RebuildCause::Layout;
    uint64_t request_id = 0;
    GridConfig config;
    std::string done;                        // reply text on success (the rebuild's figures are appended)
    std::optional<MapImage> previous_prior;  // Import: restored if the rebuild fails
  };

  MapperNode(const MapperOptions& options, Counters& counters);
  Status configure();

  // Observations (mapper_node.cpp).
  void integrate(const slam::RobotObservation& sample);
  void store_observation(std::string_view robot, uint64_t seq, int64_t stamp_ns, const ObservationView& view);
  void tick();
  void publish_changes();
  void publish_snapshot(bool bump_version);
  // Once a second: the store's size on disk and the observations DDS lost.
  void update_periodic_counters();

  // Requests and rebuilds (mapper_requests.cpp).
  void handle(const MapCommand& command);
  void handle_config(const slam::GridConfig& request);
  void handle_edit(const slam::MapEdit& edit);
  void handle_file(const slam::MapFileRequest& request);
  void start_rebuild(RebuildTicket ticket);
  void finish_rebuild(RebuildOutcome outcome);
  void run_queued_commands();
  void reply(uint64_t request_id, slam::MapResult result, const std::string& message);
  void warn(const std::string& key, const std::string& line);

  MapperOptions options_;
  Metrics metrics_;
  RateLimiter limiter_;
  std::chrono::steady_clock::duration patch_period_;
  std::chrono::steady_clock::duration snapshot_period_;

  // Loop state: touched by the loop thread only.
  std::optional<ObservationStore> store_;
  std::optional<OccupancyGrid> grid_;
  uint32_t layout_id_ = 0;    // published; changes when size, origin or resolution change
  uint32_t seen_layout_ = 0;  // grid_->layout_version() last published
  uint64_t version_ = 0;      // last published change set (patch, or grid-replacing snapshot)
  int snapshot_readers_ = 0;  // matched snapshot readers at the last tick
  std::chrono::steady_clock::time_point next_tick_;
  std::chrono::steady_clock::time_point next_snapshot_;
  std::chrono::steady_clock::time_point next_store_stat_;
  std::vector<Vec2> hits_;
  std::vector<Vec2> misses_;
  RobotFootprints footprints_;
  std::vector<Deferred> deferred_;       // observations integrated during a rebuild
  std::optional<RebuildTicket> ticket_;  // the running rebuild's
  std::deque<MapCommand> queued_;        // requests waiting for the rebuild
  MapperBatch batch_;
  slam::GridSnapshot snapshot_;
  slam::GridPatch patch_;

  MapperIntake intake_;
  RebuildWorker worker_;
  // Destroyed bottom-up: readers stop first, then writers, then the participant.
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<slam::GridSnapshot>> snapshot_writer_;
  std::unique_ptr<dds::Writer<slam::GridPatch>> patch_writer_;
  std::unique_ptr<dds::Writer<slam::MapReply>> reply_writer_;
  std::unique_ptr<dds::Reader<slam::RobotObservation>> observation_reader_;
  std::unique_ptr<dds::Reader<slam::GridConfig>> config_reader_;
  std::unique_ptr<dds::Reader<slam::MapEdit>> edit_reader_;
  std::unique_ptr<dds::Reader<slam::MapFileRequest>> file_reader_;
};

}  // namespace slam::mapper
