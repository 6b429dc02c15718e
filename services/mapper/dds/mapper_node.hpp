#pragma once
// slam-mapper's DDS edge: readers fill a locked intake; one loop thread drains it into the Mapper
// (the grid, the store, requests and rebuilds) and writes what the Mapper has for the wire: replies,
// patches at the patch rate, and snapshots when the layout changes, after rebuilds and every snapshot
// period.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <vector>

#include "common/core/counters.hpp"
#include "common/core/log.hpp"
#include "common/core/reply_cache.hpp"
#include "common/core/result.hpp"
#include "common/fastdds/fast_topics.hpp"
#include "mapper/core/correction_stage.hpp"
#include "mapper/core/mapper.hpp"
#include "mapper/core/mapper_options.hpp"
#include "mapper/dds/mapper_intake.hpp"

namespace slam::mapper {

class MapperNode {
 public:
  // Configure: the Mapper (opens the store, rebuilds the grid from it), participant, writers, first
  // snapshot, readers. A failure undoes what was done; errors about the store name its path.
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
    std::atomic<int64_t>& dropped;
    std::atomic<int64_t>& cells_changed;
    std::atomic<int64_t>& patches;
    std::atomic<int64_t>& snapshots;
    std::atomic<int64_t>& store_bytes;
    std::atomic<int64_t>& write_failures;
    std::atomic<int64_t>& observation_batches_lost;  // DDS SAMPLE_LOST on the observation reader
    std::atomic<int64_t>& requests_executed;         // requests (edits, files, layouts, poses) run
    std::atomic<int64_t>& requests_repeated;         // repeats answered from the cache or dropped
  };

  MapperNode(const MapperOptions& options, Counters& counters);
  Status configure();

  void integrate(const slam::RobotObservation& sample);
  void handle_initial_pose(const slam::InitialPose& request);
  void handle_placement_answer(const slam::PlacementAnswer& request);
  // Replies to an operator's request to the pose correction: `done` when it was carried out, else
  // the error (counted as `refused_counter`).
  void answer_operator(uint64_t request_id, const Status& outcome, std::string done,
                       const char* refused_counter);
  // Whether request `id` is new and must run; a repeat (a requester's retry) is answered from the
  // reply cache, or dropped while the first copy still runs (its reply is on the way).
  bool admit(uint64_t id);
  void send_reply(const RequestReply& reply);
  // The corrections that changed since the last call.
  void publish_corrections();
  void tick();
  void publish_changes();
  void publish_snapshot(bool new_version);
  // After a rebuild landed: its snapshot, then the replies due.
  void publish_outcomes();
  // Once a second: the store's size on disk, the observations DDS lost, the SLAM core's figures.
  void update_periodic_counters();

  MapperOptions options_;
  Counters& counters_;
  Metrics metrics_;
  RateLimitedLog log_;
  std::chrono::steady_clock::duration patch_period_;
  std::chrono::steady_clock::duration snapshot_period_;

  MapperIntake intake_;  // before mapper_: its rebuild worker wakes the loop through it
  // Loop state: touched by the loop thread only.
  std::unique_ptr<Mapper> mapper_;
  std::unique_ptr<CorrectionStage> corrections_;
  ReplyCache<RequestReply> replies_sent_;
  std::vector<correction::RobotCorrection> changed_corrections_;
  slam::PoseCorrection correction_sample_;
  int snapshot_readers_ = 0;  // matched snapshot readers at the last tick
  std::chrono::steady_clock::time_point next_tick_;
  std::chrono::steady_clock::time_point next_snapshot_;
  std::chrono::steady_clock::time_point next_store_stat_;
  std::vector<Vec2> hits_;
  std::vector<Vec2> misses_;
  MapperBatch batch_;
  slam::GridSnapshot snapshot_;
  slam::GridTiles patch_;
  EncodedTiles encoded_;  // the patch being built, reused

  // Destroyed bottom-up: readers stop first, then writers, then the participant.
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<slam::GridSnapshot>> snapshot_writer_;
  std::unique_ptr<dds::Writer<slam::GridTiles>> patch_writer_;
  std::unique_ptr<dds::Writer<slam::MapReply>> reply_writer_;
  std::unique_ptr<dds::Writer<slam::PoseCorrection>> correction_writer_;
  std::unique_ptr<dds::Reader<slam::RobotObservationBatch>> observation_reader_;
  std::unique_ptr<dds::Reader<slam::GridConfig>> config_reader_;
  std::unique_ptr<dds::Reader<slam::MapEdit>> edit_reader_;
  std::unique_ptr<dds::Reader<slam::MapFileRequest>> file_reader_;
  std::unique_ptr<dds::Reader<slam::InitialPose>> initial_pose_reader_;
  std::unique_ptr<dds::Reader<slam::PlacementAnswer>> placement_answer_reader_;
};

}  // namespace slam::mapper
