// MapperNode: configure, the loop pass, observations in, patches and snapshots out.
#include "mapper/mapper_node.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <utility>

#include "common/core/clock.hpp"
#include "mapper/map_files.hpp"
#include "mapper/mapper_msgs.hpp"
#include "mapper/rebuild.hpp"

namespace slam::mapper {
namespace {

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

MapperNode::Metrics::Metrics(Counters& c)
    : observations(c.get("observations")),
      points(c.get("points")),
      rejected(c.get("rejected")),
      dropped(c.get("dropped")),
      cells_changed(c.get("cells_changed")),
      patches(c.get("patches")),
      snapshots(c.get("snapshots")),
      rebuilds(c.get("rebuilds")),
      requests(c.get("requests")),
      request_errors(c.get("request_errors")),
      store_observations(c.get("store_observations")),
      store_bytes(c.get("store_bytes")),
      store_errors(c.get("store_errors")),
      write_failures(c.get("write_failures")),
      robot_hits_filtered(c.get("robot_hits_filtered")),
      observations_lost(c.get("observations_lost")) {}

ObservationView MapperNode::Deferred::view() const {
  ObservationView v;
  v.x = x;
  v.y = y;
  v.theta = theta;
  v.has_heading = has_heading;
  v.hits = hits;
  v.misses = misses;
  return v;
}

MapperNode::MapperNode(const MapperOptions& options, Counters& counters)
    : options_(options),
      metrics_(counters),
      patch_period_(seconds(1.0 / options.patch_rate_hz)),
      snapshot_period_(seconds(options.snapshot_period_s)),
      footprints_(options.robot_filter),
      intake_(options.max_queued_observations),
      worker_([this] { intake_.notify(); }) {}

MapperNode::~MapperNode() {
  // Stop the inflow first, then land a running rebuild so what it held aside reaches the store.
  observation_reader_.reset();
  config_reader_.reset();
  edit_reader_.reset();
  file_reader_.reset();
  if (auto outcome = worker_.wait()) finish_rebuild(std::move(*outcome));
  if (store_) {
    if (Status s = store_->flush(); !s) spdlog::error("{}", s.message());
  }
}

Result<std::unique_ptr<MapperNode>> MapperNode::create(const MapperOptions& options, Counters& counters) {
  std::unique_ptr<MapperNode> node(new MapperNode(options, counters));
  SLAM_TRY(node->configure());
  return node;
}

Status MapperNode::configure() {
  auto store = open_store(options_.store, StoreOptions{options_.store_batch});
  if (!store) return store.error();
  store_.emplace(std::move(*store));
  auto config = startup_config(options_.grid, *store_);
  if (!config) return config.error();
  const auto started = std::chrono::steady_clock::now();
  RebuildStats stats;
  auto grid = rebuild_grid(*config, *store_, &stats);
  if (!grid) return grid.error();
  grid_.emplace(std::move(*grid));
  const auto took = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  spdlog::info(
      "store {}: {} observations, {} obstructions, {} prior cells rebuilt in {:.3f} s ({}x{} cells of {} m)",
      options_.store, stats.observations, stats.obstructions, stats.prior_cells, took, grid_->width(),
      grid_->height(), grid_->resolution());
  if (stats.rejected > 0)
    spdlog::warn("store: {} observations rejected: {}", stats.rejected, stats.first_error);
  auto count = store_->count();
  if (!count) return count.error();
  metrics_.store_observations.store(*count);
  update_periodic_counters();

  // Layout ids continue from the clock so a restarted mapper's ids differ from the last run's.
  layout_id_ = static_cast<uint32_t>(now_ns() / 1000000000);
  seen_layout_ = grid_->layout_version();
  (void)grid_->take_dirty();

  auto participant = dds::Participant::create(options_.service.domain, "slam-mapper");
  if (!participant) return participant.error();
  participant_ = std::move(*participant);
  auto snapshots = dds::make_writer(*participant_, dds::kGridSnapshot);
  if (!snapshots) return snapshots.error();
  snapshot_writer_ = std::move(*snapshots);
  auto patches = dds::make_writer(*participant_, dds::kGridPatch);
  if (!patches) return patches.error();
  patch_writer_ = std::move(*patches);
  auto replies = dds::make_writer(*participant_, dds::kMapReply);
  if (!replies) return replies.error();
  reply_writer_ = std::move(*replies);
  publish_snapshot(false);

  // Readers last: from here on callbacks run, and everything they touch exists.
  auto observations =
      dds::make_reader(*participant_, dds::kRobotObservation,
                       [this](const slam::RobotObservation& o, const auto&) { intake_.push(o); });
  if (!observations) return observations.error();
  observation_reader_ = std::move(*observations);
  auto configs =
      dds::make_reader(*participant_, dds::kGridConfig,
                       [this](const slam::GridConfig& c, const auto&) { intake_.push(MapCommand{c}); });
  if (!configs) return configs.error();
  config_reader_ = std::move(*configs);
  auto edits = dds::make_reader(*participant_, dds::kMapEdit,
                                [this](const slam::MapEdit& e, const auto&) { intake_.push(MapCommand{e}); });
  if (!edits) return edits.error();
  edit_reader_ = std::move(*edits);
  auto files =
      dds::make_reader(*participant_, dds::kMapFileRequest,
                       [this](const slam::MapFileRequest& r, const auto&) { intake_.push(MapCommand{r}); });
  if (!files) return files.error();
  file_reader_ = std::move(*files);

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
    warn("dropped", std::to_string(batch_.dropped) + " observations dropped: more than " +
                        std::to_string(options_.max_queued_observations) + " waiting for the map loop");
  }
  if (auto outcome = worker_.take()) finish_rebuild(std::move(*outcome));
  for (const slam::RobotObservation& o : batch_.observations) integrate(o);
  for (MapCommand& c : batch_.commands) queued_.push_back(std::move(c));
  run_queued_commands();

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
  if (view) {
    const size_t moved = footprints_.apply(robot, {view->x, view->y}, monotonic_ns(), hits_, misses_);
    if (moved > 0) {
      bump(metrics_.robot_hits_filtered, static_cast<int64_t>(moved));
      view->hits = hits_;
      view->misses = misses_;
    }
  }
  Result<IntegrateStats> stats =
      view ? grid_->integrate(*view) : Result<IntegrateStats>(Error{view.message()});
  if (!stats) {
    bump(metrics_.rejected);
    warn("reject:" + std::string(robot), "observation of robot '" + std::string(robot) + "' seq " +
                                             std::to_string(sample.seq()) + " rejected: " + stats.message());
    return;
  }
  bump(metrics_.observations);
  bump(metrics_.points, static_cast<int64_t>(hits_.size() + misses_.size()));
  if (stats->clipped > 0)
    warn("clip:" + std::string(robot), "robot '" + std::string(robot) +
                                           "': " + std::to_string(stats->clipped) +
                                           " point(s) clipped: " + kClipReason);
  if (worker_.busy()) {
    // The rebuild must see the store as it was when it started: keep this for the new grid.
    deferred_.push_back(Deferred{std::string(robot), sample.seq(), sample.stamp_ns(), view->x, view->y,
                                 view->theta, view->has_heading, hits_, misses_});
    return;
  }
  store_observation(robot, sample.seq(), sample.stamp_ns(), *view);
}

void MapperNode::store_observation(std::string_view robot, uint64_t seq, int64_t stamp_ns,
                                   const ObservationView& view) {
  if (Status s = store_->append(robot, seq, stamp_ns, view); !s) {
    bump(metrics_.store_errors);
    warn("store", "observation of robot '" + std::string(robot) +
                      "' not stored (the map has it until restart): " + s.message());
    return;
  }
  bump(metrics_.store_observations);
}

void MapperNode::tick() {
  // One commit per tick bounds what a crash can lose to one patch period, and a published patch
  // implies its observations are on disk.
  if (!worker_.busy()) {
    if (Status s = store_->flush(); !s) {
      bump(metrics_.store_errors);
      warn("store", s.message());
    }
  }
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
  if (grid_->layout_version() != seen_layout_) {  // the grid grew: a patch cannot describe it
    publish_snapshot(true);
    return;
  }
  const auto box = grid_->take_dirty();
  if (!box) return;
  fill_patch(*grid_, *box, layout_id_, version_ + 1, now_ns(), &patch_);
  if (!patch_writer_->write(patch_)) {
    // Receivers would see a gap: a snapshot with the changes resynchronises them.
    bump(metrics_.write_failures);
    publish_snapshot(true);
    return;
  }
  ++version_;
  bump(metrics_.patches);
  bump(metrics_.cells_changed, int64_t{box->width} * box->height);
}

void MapperNode::publish_snapshot(bool bump_version) {
  if (grid_->layout_version() != seen_layout_) {
    seen_layout_ = grid_->layout_version();
    ++layout_id_;
  }
  (void)grid_->take_dirty();  // a snapshot carries every change
  if (bump_version) ++version_;
  fill_snapshot(*grid_, layout_id_, version_, now_ns(), &snapshot_);
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
  if (observation_reader_)
    metrics_.observations_lost.store(observation_reader_->samples_lost(), std::memory_order_relaxed);
  next_store_stat_ = std::chrono::steady_clock::now() + std::chrono::seconds(1);
}

void MapperNode::warn(const std::string& key, const std::string& line) {
  uint64_t suppressed = 0;
  if (!limiter_.allow(key, &suppressed)) return;
  if (suppressed > 0)
    spdlog::warn("{} ({} similar lines suppressed)", line, suppressed);
  else
    spdlog::warn("{}", line);
}

}  // namespace slam::mapper
