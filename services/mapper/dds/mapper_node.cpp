// MapperNode: configure, the loop pass, samples into the Mapper, patches, snapshots and replies out.
#include "mapper/dds/mapper_node.hpp"

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <utility>

#include "common/core/clock.hpp"
#include "mapper/dds/mapper_msgs.hpp"

namespace slam::mapper {
namespace {

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

MapperNode::Metrics::Metrics(Counters& c)
    : dropped(c.get("dropped")),
      cells_changed(c.get("cells_changed")),
      patches(c.get("patches")),
      snapshots(c.get("snapshots")),
      store_bytes(c.get("store_bytes")),
      write_failures(c.get("write_failures")),
      observation_batches_lost(c.get("observation_batches_lost")),
      requests_executed(c.get("requests_executed")),
      requests_repeated(c.get("requests_repeated")) {}

MapperNode::MapperNode(const MapperOptions& options, Counters& counters)
    : options_(options),
      counters_(counters),
      metrics_(counters),
      patch_period_(seconds(1.0 / options.patch_rate_hz)),
      snapshot_period_(seconds(options.snapshot_period_s)),
      intake_(options.max_queued_observations) {}

MapperNode::~MapperNode() {
  // Stop the inflow first, then land a running rebuild so what it held aside reaches the store.
  observation_reader_.reset();
  config_reader_.reset();
  edit_reader_.reset();
  file_reader_.reset();
  initial_pose_reader_.reset();
  placement_answer_reader_.reset();
  if (mapper_ && snapshot_writer_) {
    mapper_->wait_for_rebuild();
    publish_outcomes();
  }
}

Result<std::unique_ptr<MapperNode>> MapperNode::create(const MapperOptions& options, Counters& counters) {
  std::unique_ptr<MapperNode> node(new MapperNode(options, counters));
  SLAM_TRY(node->configure());
  return node;
}

Status MapperNode::configure() {
  // Layout ids continue from the clock so a restarted mapper's ids differ from the last run's.
  auto mapper = Mapper::create(options_, counters_, static_cast<uint32_t>(now_ns() / 1000000000),
                               [this] { intake_.notify(); });
  if (!mapper) return mapper.error();
  mapper_ = std::move(*mapper);
  if (options_.localise_only && !mapper_->has_walls()) {
    return Error{fmt::format(
        "--localise-only: the store {} holds no map to localise on; map the building first, or import a "
        "map: slam-mapper --store {} --import map.yaml",
        options_.store, options_.store)};
  }
  correction::CorrectorOptions slam_options;
  slam_options.old_age_s = options_.slam_old_age_s;
  slam_options.wall_heading = options_.slam_wall_heading == "on";
  slam_options.global_localisation = options_.slam_global_localisation == "on";
  if (options_.slam_lost_robots == "off") slam_options.lost_after_unmatched = 0;
  slam_options.point_refine = options_.slam_point_refine == "on";
  slam_options.odometry_calibration = options_.slam_odometry_calibration == "on";
  slam_options.relocalise = options_.slam_relocalise == "on";
  slam_options.localise_only = options_.localise_only;
  slam_options.match_threads = 1;  // the map loop keeps integrating while keyframes are matched
  corrections_ = std::make_unique<CorrectionStage>(options_.slam_enabled(), slam_options);
  corrections_->set_wake([this] { intake_.notify(); });
  SLAM_TRY(corrections_->restore(*mapper_));
  update_periodic_counters();

  auto participant = dds::Participant::create(options_.service.domain, "slam-mapper");
  if (!participant) return participant.error();
  participant_ = std::move(*participant);
  auto snapshots = dds::make_writer(*participant_, dds::kGridSnapshot);
  if (!snapshots) return snapshots.error();
  snapshot_writer_ = std::move(*snapshots);
  auto patches = dds::make_writer(*participant_, dds::kGridTiles);
  if (!patches) return patches.error();
  patch_writer_ = std::move(*patches);
  auto replies = dds::make_writer(*participant_, dds::kMapReply);
  if (!replies) return replies.error();
  reply_writer_ = std::move(*replies);
  auto corrections = dds::make_writer(*participant_, dds::kPoseCorrection);
  if (!corrections) return corrections.error();
  correction_writer_ = std::move(*corrections);
  publish_corrections();
  publish_snapshot(false);

  // Readers last: from here on callbacks run, and everything they touch exists.
  auto observations =
      dds::make_reader(*participant_, dds::kRobotObservations,
                       [this](const slam::RobotObservationBatch& b, const auto&) { intake_.push(b); });
  if (!observations) return observations.error();
  observation_reader_ = std::move(*observations);
  auto configs = dds::make_reader(
      *participant_, dds::kGridConfig,
      [this](const slam::GridConfig& c, const auto&) { intake_.push(MapCommand{to_request(c)}); });
  if (!configs) return configs.error();
  config_reader_ = std::move(*configs);
  auto edits = dds::make_reader(*participant_, dds::kMapEdit, [this](const slam::MapEdit& e, const auto&) {
    intake_.push(MapCommand{to_request(e)});
  });
  if (!edits) return edits.error();
  edit_reader_ = std::move(*edits);
  auto files = dds::make_reader(
      *participant_, dds::kMapFileRequest,
      [this](const slam::MapFileRequest& r, const auto&) { intake_.push(MapCommand{to_request(r)}); });
  if (!files) return files.error();
  file_reader_ = std::move(*files);
  auto poses = dds::make_reader(*participant_, dds::kInitialPose,
                                [this](const slam::InitialPose& r, const auto&) { intake_.push(r); });
  if (!poses) return poses.error();
  initial_pose_reader_ = std::move(*poses);
  auto answers = dds::make_reader(*participant_, dds::kPlacementAnswer,
                                  [this](const slam::PlacementAnswer& r, const auto&) { intake_.push(r); });
  if (!answers) return answers.error();
  placement_answer_reader_ = std::move(*answers);

  next_tick_ = std::chrono::steady_clock::now() + patch_period_;
  spdlog::info("mapper ready on domain {} (patches at {} Hz, snapshots every {} s)", options_.service.domain,
               options_.patch_rate_hz, options_.snapshot_period_s);
  return Status::ok();
}

void MapperNode::run_once() {
  intake_.wait_until(next_tick_);
  intake_.drain(batch_);
  if (batch_.dropped > 0) {
    bump(metrics_.dropped, static_cast<int64_t>(batch_.dropped));
    log_.warn("dropped", "{} observations dropped: more than {} waiting for the map loop", batch_.dropped,
              options_.max_queued_observations);
  }
  mapper_->poll_rebuild();
  publish_outcomes();
  for (const slam::RobotObservation& o : batch_.observations) integrate(o);
  corrections_->step(*mapper_, now_ns(), monotonic_ns());
  for (MapCommand& c : batch_.commands) {
    if (!admit(std::visit([](const auto& r) { return r.request_id; }, c))) continue;
    if (const auto* edit = std::get_if<EditRequest>(&c); edit && edit->kind == EditKind::ResetRobot)
      corrections_->reset_robot(edit->robot_id);
    mapper_->submit(std::move(c));
  }
  for (const slam::InitialPose& p : batch_.initial_poses)
    if (admit(p.request_id())) handle_initial_pose(p);
  for (const slam::PlacementAnswer& a : batch_.placement_answers)
    if (admit(a.request_id())) handle_placement_answer(a);
  publish_outcomes();
  publish_corrections();

  const auto now = std::chrono::steady_clock::now();
  if (now >= next_tick_) {
    tick();
    next_tick_ += patch_period_;
    if (next_tick_ <= now) next_tick_ = now + patch_period_;  // fell behind: do not burst
  }
}

void MapperNode::integrate(const slam::RobotObservation& sample) {
  const std::string_view robot(sample.robot_id().c_str(), sample.robot_id().size());
  auto view = to_view(sample, hits_, misses_);
  if (!view) return mapper_->reject(robot, sample.seq(), view.message());
  corrections_->add(
      *mapper_, RobotScan{robot, sample.seq(), sample.stamp_ns(), *view, 0, Pose{}, sample.robot_stamp_ns()},
      monotonic_ns());
}

void MapperNode::handle_initial_pose(const slam::InitialPose& request) {
  const std::string robot = request.robot_id().to_string();
  const Pose pose{request.pose().x(), request.pose().y(), request.pose().theta()};
  answer_operator(request.request_id(), corrections_->set_initial_pose(*mapper_, robot, pose),
                  fmt::format("initial pose of {} set to ({:.3f}, {:.3f}, {:.1f} deg)", robot, pose.x, pose.y,
                              pose.theta * 180.0 / 3.141592653589793),
                  "initial_poses_rejected");
}

void MapperNode::handle_placement_answer(const slam::PlacementAnswer& request) {
  const std::string robot = request.robot_id().to_string();
  const bool accept = request.verdict() == slam::PLACEMENT_ACCEPT;
  answer_operator(request.request_id(), corrections_->answer_placement(robot, accept),
                  fmt::format("placement of {} {}", robot, accept ? "accepted" : "rejected"),
                  "placement_answers_refused");
}

void MapperNode::answer_operator(uint64_t request_id, const Status& outcome, std::string done,
                                 const char* refused_counter) {
  RequestReply reply{request_id, RequestResult::Ok, std::move(done)};
  if (outcome) {
    spdlog::info("{}", reply.message);
  } else {
    reply.result = failure_result(outcome.code());
    reply.message = outcome.message();
    bump(counters_.get(refused_counter));
  }
  send_reply(reply);
}

bool MapperNode::admit(uint64_t id) {
  const auto verdict = replies_sent_.admit(id);
  if (verdict.admission == Admission::Execute) {
    bump(metrics_.requests_executed);
    return true;
  }
  bump(metrics_.requests_repeated);
  if (verdict.reply && !reply_writer_->write(to_reply(*verdict.reply))) bump(metrics_.write_failures);
  return false;
}

void MapperNode::send_reply(const RequestReply& reply) {
  replies_sent_.complete(reply.request_id, reply);
  if (!reply_writer_->write(to_reply(reply))) bump(metrics_.write_failures);
}

void MapperNode::publish_corrections() {
  changed_corrections_.clear();
  corrections_->take_changed(changed_corrections_);
  const int64_t stamp = now_ns();
  for (const auto& c : changed_corrections_) {
    fill_correction(c, stamp, &correction_sample_);
    if (!correction_writer_->write(correction_sample_)) bump(metrics_.write_failures);
  }
}

void MapperNode::publish_outcomes() {
  if (mapper_->take_swapped()) publish_snapshot(true);
  for (const RequestReply& r : mapper_->take_replies()) send_reply(r);
}

void MapperNode::tick() {
  // One commit per tick bounds what a crash can lose to one patch period, and a published patch
  // implies its observations are on disk.
  mapper_->commit();
  publish_changes();
  // A reader that just matched got the last snapshot from the writer's history, which may predate
  // the patches it missed: send a current one rather than leave it waiting for the period.
  const int readers = snapshot_writer_->matched_readers();
  const bool joined = readers > snapshot_readers_;
  snapshot_readers_ = readers;
  const auto now = std::chrono::steady_clock::now();
  if (joined || now >= next_snapshot_) publish_snapshot(false);
  if (now >= next_store_stat_) update_periodic_counters();
}

void MapperNode::publish_changes() {
  if (mapper_->needs_snapshot()) {  // the grid grew: a patch cannot describe it
    publish_snapshot(true);
    return;
  }
  if (!mapper_->grid().dirty_tiles().any()) return;
  const PublishStamp stamp = mapper_->next_patch();
  fill_patch(mapper_->grid(), stamp.layout_id, stamp.version, now_ns(), encoded_, &patch_);
  if (!patch_writer_->write(patch_)) {
    // Receivers would see a gap: a snapshot with the changes resynchronises them.
    bump(metrics_.write_failures);
    publish_snapshot(true);
    return;
  }
  mapper_->patch_sent();
  bump(metrics_.patches);
  bump(metrics_.cells_changed, static_cast<int64_t>(encoded_.cells()));
}

void MapperNode::publish_snapshot(bool new_version) {
  const PublishStamp stamp = mapper_->prepare_snapshot(new_version);
  fill_snapshot(mapper_->grid(), stamp.layout_id, stamp.version, now_ns(), &snapshot_);
  readers_hold(mapper_->grid().classes(), encoded_);  // the next patch's XOR coding starts from it
  next_snapshot_ = std::chrono::steady_clock::now() + snapshot_period_;
  if (!snapshot_writer_->write(snapshot_)) {
    bump(metrics_.write_failures);
    next_snapshot_ = std::chrono::steady_clock::now() + patch_period_;  // retry soon
    return;
  }
  bump(metrics_.snapshots);
}

void MapperNode::update_periodic_counters() {
  int64_t bytes = 0;
  for (const char* suffix : {"", "-wal"}) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(options_.store + suffix, ec);
    if (!ec) bytes += static_cast<int64_t>(size);
  }
  metrics_.store_bytes.store(bytes, std::memory_order_relaxed);
  const correction::CorrectorStats& st = corrections_->stats();
  counters_.get("slam_keyframes").store(st.keyframes, std::memory_order_relaxed);
  counters_.get("slam_matched").store(st.matched, std::memory_order_relaxed);
  counters_.get("slam_unmatched").store(st.unmatched, std::memory_order_relaxed);
  counters_.get("slam_standing").store(st.standing, std::memory_order_relaxed);
  counters_.get("slam_closures_tried").store(st.closures_tried, std::memory_order_relaxed);
  counters_.get("slam_closures_accepted").store(st.closures_accepted, std::memory_order_relaxed);
  counters_.get("slam_closures_rejected").store(st.closures_rejected, std::memory_order_relaxed);
  counters_.get("slam_optimisations").store(st.optimisations, std::memory_order_relaxed);
  counters_.get("slam_segments").store(st.segments, std::memory_order_relaxed);
  counters_.get("slam_wall_headings").store(st.wall_headings, std::memory_order_relaxed);
  counters_.get("slam_point_refined").store(st.point_refined, std::memory_order_relaxed);
  counters_.get("slam_rejected_inputs").store(st.rejected_inputs, std::memory_order_relaxed);
  counters_.get("slam_clock_steps").store(st.clock_steps, std::memory_order_relaxed);
  counters_.get("slam_placement_searches").store(st.placement_searches, std::memory_order_relaxed);
  counters_.get("slam_robots_placed").store(st.robots_placed, std::memory_order_relaxed);
  counters_.get("slam_robots_lost").store(st.robots_lost, std::memory_order_relaxed);
  counters_.get("slam_placements_refused").store(st.placements_refused, std::memory_order_relaxed);
  counters_.get("slam_unplaced_observations_dropped")
      .store(corrections_->dropped_observations(), std::memory_order_relaxed);
  counters_.get("slam_localised_observations")
      .store(corrections_->localised_observations(), std::memory_order_relaxed);
  counters_.get("slam_trail_searches").store(st.trail_searches, std::memory_order_relaxed);
  counters_.get("slam_ties_tried").store(st.ties_tried, std::memory_order_relaxed);
  counters_.get("slam_ties_skipped").store(st.ties_skipped, std::memory_order_relaxed);
  counters_.get("slam_wide_skipped").store(st.wide_skipped, std::memory_order_relaxed);
  counters_.get("slam_placed_by_odometry").store(st.placed_by_odometry, std::memory_order_relaxed);
  counters_.get("slam_backlog").store(st.backlog, std::memory_order_relaxed);
  counters_.get("slam_load").store(st.load, std::memory_order_relaxed);
  counters_.get("slam_held").store(corrections_->held_observations(), std::memory_order_relaxed);
  counters_.get("slam_held_open").store(st.open_messages, std::memory_order_relaxed);

  if (observation_reader_)
    metrics_.observation_batches_lost.store(observation_reader_->samples_lost(), std::memory_order_relaxed);
  next_store_stat_ = std::chrono::steady_clock::now() + std::chrono::seconds(1);
}

}  // namespace slam::mapper
