// Mapper: observations in, requests answered, rebuilds landed, publication numbered.
// Every request gets one reply; a refused request leaves the map and the store as they were.
#include "mapper/core/mapper.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <type_traits>
#include <utility>

#include "common/core/cell_class.hpp"
#include "mapper/core/map_error.hpp"
#include "mapper/core/map_files.hpp"
#include "mapper/core/rebuild.hpp"
#include "mapper/core/trajectory_export.hpp"

namespace slam::mapper {
namespace {

std::string point_text(double x, double y) {
  return "(" + std::to_string(x) + ", " + std::to_string(y) + ")";
}

std::string layout_text(const GridConfig& c) {
  return std::to_string(c.resolution) + " m/cell, origin " + point_text(c.origin_x, c.origin_y) + ", " +
         std::to_string(c.width_m) + " x " + std::to_string(c.height_m) + " m, inflation " +
         std::to_string(c.inflation_radius) + " m" + (c.legacy_mode ? ", legacy mode" : "");
}

bool same_geometry(const OccupancyGrid& a, const OccupancyGrid& b) {
  return a.width() == b.width() && a.height() == b.height() && a.resolution() == b.resolution() &&
         a.origin_x() == b.origin_x() && a.origin_y() == b.origin_y();
}

RequestResult file_result(const FileOutcome& outcome) {
  return outcome.ok() ? RequestResult::Ok : failure_result(outcome.failure);
}

}  // namespace

RequestResult failure_result(ErrorCode code) {
  if (code.domain() != ErrorDomain::Map) return RequestResult::InvalidRequest;
  switch (static_cast<MapError>(code.value())) {
    case MapError::InvalidRequest:
      return RequestResult::InvalidRequest;
    case MapError::Io:
      return RequestResult::IoError;
    case MapError::BadFile:
      return RequestResult::BadFile;
    case MapError::UnknownRobot:
      return RequestResult::UnknownRobot;
  }
  return RequestResult::InvalidRequest;
}

Result<GridConfig> requested_config(const LayoutRequest& request, const GridConfig& current) {
  GridConfig c = current;
  c.resolution = request.resolution;
  c.origin_x = request.origin_x;
  c.origin_y = request.origin_y;
  if (request.width_m != 0.0) c.width_m = request.width_m;
  if (request.height_m != 0.0) c.height_m = request.height_m;
  if (!(request.inflation_radius < 0.0))
    c.inflation_radius = request.inflation_radius;  // NaN: validated below
  c.legacy_mode = request.legacy_mode;
  if (Status s = validate(c); !s) return s.error();
  return c;
}

Mapper::Metrics::Metrics(Counters& c)
    : observations(c.get("observations")),
      points(c.get("points")),
      rejected(c.get("rejected")),
      rebuilds(c.get("rebuilds")),
      requests(c.get("requests")),
      request_errors(c.get("request_errors")),
      store_observations(c.get("store_observations")),
      store_errors(c.get("store_errors")),
      robot_hits_filtered(c.get("robot_hits_filtered")),
      rerenders_partial(c.get("rerenders_partial")),
      rerender_observations(c.get("rerender_observations")),
      compactions(c.get("compactions")),
      compacted_observations(c.get("compacted_observations")) {}

ObservationView Mapper::Deferred::view() const {
  return ObservationView{x, y, theta, has_heading, hits, misses};
}

Mapper::Mapper(const MapperOptions& options, Counters& counters, uint32_t first_layout_id,
               std::function<void()> on_rebuild_done)
    : options_(options),
      metrics_(counters),
      layout_id_(first_layout_id),
      footprints_(options.robot_filter),
      worker_(std::move(on_rebuild_done)) {}

Mapper::~Mapper() {
  wait_for_rebuild();
  commit();
}

Result<std::unique_ptr<Mapper>> Mapper::create(const MapperOptions& options, Counters& counters,
                                               uint32_t first_layout_id,
                                               std::function<void()> on_rebuild_done) {
  std::unique_ptr<Mapper> mapper(new Mapper(options, counters, first_layout_id, std::move(on_rebuild_done)));
  SLAM_TRY(mapper->open());
  return mapper;
}

Status Mapper::open() {
  auto store = open_store(options_.store, StoreOptions{options_.store_batch});
  if (!store) return store.error();
  store_.emplace(std::move(*store));
  auto config = startup_config(options_.grid, *store_);
  if (!config) return config.error();
  const auto started = std::chrono::steady_clock::now();
  auto keyframes = store_->keyframes();
  if (!keyframes) return keyframes.error();
  for (const Keyframe& k : *keyframes) corrections_.set(k.id, k.map_from_odom);
  RebuildStats stats;
  auto grid = rebuild_grid(*config, *store_, &stats, corrections_, &index_);
  if (!grid) return grid.error();
  grid_.emplace(std::move(*grid));
  const auto took = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  spdlog::info(
      "store {}: {} observations, {} keyframes, {} obstructions, {} prior cells rebuilt in {:.3f} s ({}x{} "
      "cells of {} m; footprint index {} groups, {} kB)",
      options_.store, stats.observations, corrections_.size(), stats.obstructions, stats.prior_cells, took,
      grid_->width(), grid_->height(), grid_->resolution(), index_.groups().size(),
      index_.memory_bytes() / 1024);
  if (stats.rejected > 0)
    spdlog::warn("store: {} observations rejected: {}", stats.rejected, stats.first_error);
  for (const FootprintGroup& g : index_.groups())
    newest_stamp_ns_ = std::max(newest_stamp_ns_, g.first_stamp_ns);
  auto prior = store_->load_prior();
  if (!prior) return prior.error();
  has_prior_ = prior->has_value();
  auto count = store_->count();
  if (!count) return count.error();
  metrics_.store_observations.store(*count);
  seen_layout_ = grid_->layout_version();
  grid_->clear_dirty();
  return Status::ok();
}

bool Mapper::has_walls() const {
  return std::ranges::any_of(grid_->classes(), [](uint8_t c) { return is_wall(c); });
}

void Mapper::reject(std::string_view robot_id, uint64_t seq, const std::string& reason) {
  bump(metrics_.rejected);
  const std::string robot(robot_id);
  log_.warn("reject:" + robot, "observation of robot '{}' seq {} rejected: {}", robot, seq, reason);
}

void Mapper::integrate(const RobotScan& scan, int64_t now_ns) {
  loop_now_ns_ = now_ns;
  odom_hits_.assign(scan.view.hits.begin(), scan.view.hits.end());
  odom_misses_.assign(scan.view.misses.begin(), scan.view.misses.end());
  // Uncorrected, the odometry buffers are the map frame's; corrected, the filter decides in the map
  // frame and moves the same points in both, so what is stored re-renders to what is integrated.
  const bool corrected = !is_identity(scan.map_from_odom);
  ObservationView view = corrected ? to_map_frame(scan.map_from_odom, scan.view, hits_, misses_) : scan.view;
  std::vector<Vec2>& map_hits = corrected ? hits_ : odom_hits_;
  std::vector<Vec2>& map_misses = corrected ? misses_ : odom_misses_;
  const size_t moved =
      footprints_.apply(scan.robot_id, {view.x, view.y}, now_ns, map_hits, map_misses,
                        corrected ? &odom_hits_ : nullptr, corrected ? &odom_misses_ : nullptr);
  bump(metrics_.robot_hits_filtered, static_cast<int64_t>(moved));
  view.hits = map_hits;
  view.misses = map_misses;
  ObservationView odom = scan.view;
  odom.hits = odom_hits_;
  odom.misses = odom_misses_;
  Result<IntegrateStats> stats = grid_->integrate(view);
  if (!stats) return reject(scan.robot_id, scan.seq, stats.message());
  bump(metrics_.observations);
  bump(metrics_.points, static_cast<int64_t>(map_hits.size() + map_misses.size()));
  if (stats->clipped > 0) {
    const std::string robot(scan.robot_id);
    log_.warn("clip:" + robot, "robot '{}': {} point(s) clipped: {}", robot, stats->clipped, kClipReason);
  }
  if (worker_.busy()) {
    // The rebuild must see the store as it was when it started: keep this for the new grid.
    deferred_.push_back(Deferred{std::string(scan.robot_id), scan.seq, scan.stamp_ns, scan.robot_stamp_ns,
                                 scan.keyframe_id, scan.map_from_odom, odom.x, odom.y, odom.theta,
                                 odom.has_heading, odom_hits_, odom_misses_});
    return;
  }
  store_observation(scan.robot_id, scan.seq, scan.stamp_ns, scan.keyframe_id, odom, scan.robot_stamp_ns,
                    scan.map_from_odom, box_of(view));
}

void Mapper::store_observation(std::string_view robot, uint64_t seq, int64_t stamp_ns, KeyframeId keyframe_id,
                               const ObservationView& odom, int64_t robot_stamp_ns, const Pose& drawn,
                               const MapBox& box) {
  if (Status s = store_->append(robot, seq, stamp_ns, keyframe_id, odom, robot_stamp_ns); !s) {
    bump(metrics_.store_errors);
    log_.warn("store", "observation of robot '{}' not stored (the map has it until restart): {}", robot,
              s.message());
    return;
  }
  index_.add(keyframe_id, store_->last_row(), drawn, box, stamp_ns);
  newest_stamp_ns_ = std::max(newest_stamp_ns_, stamp_ns);
  bump(metrics_.store_observations);
}

void Mapper::commit() {
  if (worker_.busy() || !store_) return;
  if (Status s = store_->flush(); !s) {
    bump(metrics_.store_errors);
    log_.warn("store", "{}", s.message());
  }
}

std::vector<RequestReply> Mapper::take_replies() {
  return std::exchange(replies_, {});
}

PublishStamp Mapper::prepare_snapshot(bool new_version) {
  if (grid_->layout_version() != seen_layout_) {
    seen_layout_ = grid_->layout_version();
    ++layout_id_;
  }
  grid_->clear_dirty();  // a snapshot carries every change
  if (new_version) ++version_;
  return {layout_id_, version_};
}

bool Mapper::take_swapped() {
  return std::exchange(swapped_, false);
}

Status Mapper::save_keyframes(std::span<const Keyframe> keyframes) {
  if (Status s = store_->save_keyframes(keyframes); !s) {
    bump(metrics_.store_errors);
    return s;
  }
  for (const Keyframe& k : keyframes) corrections_.set(k.id, k.map_from_odom);
  return Status::ok();
}

void Mapper::rerender() {
  rerender_waiting_ = true;
  run_queued_commands();
}

void Mapper::submit(MapCommand command) {
  queued_.push_back(std::move(command));
  run_queued_commands();
}

void Mapper::poll_rebuild() {
  if (auto outcome = worker_.take()) finish_rebuild(std::move(*outcome));
  run_queued_commands();
  maybe_compact();
}

void Mapper::wait_for_rebuild() {
  if (auto outcome = worker_.wait()) finish_rebuild(std::move(*outcome));
  run_queued_commands();
}

void Mapper::run_queued_commands() {
  while (!worker_.busy() && !queued_.empty()) {
    MapCommand command = std::move(queued_.front());
    queued_.pop_front();
    handle(command);
  }
  if (!worker_.busy() && rerender_waiting_) {
    rerender_waiting_ = false;
    start_rerender(std::exchange(full_rerender_waiting_, false));
  }
}

void Mapper::handle(const MapCommand& command) {
  bump(metrics_.requests);
  std::visit(
      [this](const auto& c) {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, LayoutRequest>)
          handle_layout(c);
        else if constexpr (std::is_same_v<T, EditRequest>)
          handle_edit(c);
        else
          handle_file(c);
      },
      command);
}

void Mapper::handle_layout(const LayoutRequest& request) {
  auto config = requested_config(request, grid_->config());
  if (!config) {
    reply(request.request_id, RequestResult::InvalidRequest, "grid config refused: " + config.message());
    return;
  }
  if (same_layout(*config, grid_->config())) {
    reply(request.request_id, RequestResult::Ok, "grid layout unchanged (" + layout_text(*config) + ")");
    return;
  }
  start_rebuild(RebuildTicket{RebuildCause::Layout, request.request_id, *config,
                              "grid layout changed to " + layout_text(*config), std::nullopt});
}

void Mapper::handle_edit(const EditRequest& edit) {
  const uint64_t id = edit.request_id;
  const double x = edit.point.x;
  const double y = edit.point.y;
  switch (edit.kind) {
    case EditKind::Obstruct: {
      const auto cell = grid_->cell_at({x, y});
      const bool already = cell && (grid_->cell_class(cell->x, cell->y) & kCellObstructed) != 0;
      if (Status s = grid_->obstruct(x, y); !s) return reply(id, RequestResult::InvalidRequest, s.message());
      if (already)
        return reply(id, RequestResult::Ok, "the cell at " + point_text(x, y) + " is already obstructed");
      if (Status s = store_->add_obstruction({x, y}); !s) {
        (void)grid_->unobstruct(x, y);
        bump(metrics_.store_errors);
        return reply(id, RequestResult::IoError, s.message());
      }
      return reply(id, RequestResult::Ok, "obstructed the cell at " + point_text(x, y));
    }
    case EditKind::Unobstruct: {
      if (!std::isfinite(x) || !std::isfinite(y))
        return reply(id, RequestResult::InvalidRequest, "point is not finite");
      const std::vector<Vec2> removed = grid_->unobstruct(x, y);
      for (const Vec2& p : removed) {
        if (Status s = store_->remove_obstruction(p); !s) {
          bump(metrics_.store_errors);
          return reply(id, RequestResult::IoError,
                       s.message() + " (the map no longer shows it; a restart would)");
        }
      }
      return reply(id, RequestResult::Ok,
                   removed.empty() ? "no manual obstruction at " + point_text(x, y)
                                   : "removed " + std::to_string(removed.size()) + " obstruction(s) at " +
                                         point_text(x, y));
    }
    case EditKind::ClearObstructions: {
      if (Status s = store_->clear_obstructions(); !s) {
        bump(metrics_.store_errors);
        return reply(id, RequestResult::IoError, s.message());
      }
      const size_t count = grid_->obstructions().size();
      grid_->clear_obstructions();
      return reply(id, RequestResult::Ok, "cleared " + std::to_string(count) + " manual obstruction(s)");
    }
    case EditKind::ResetRobot: {
      const std::string& robot = edit.robot_id;
      if (robot.empty()) return reply(id, RequestResult::InvalidRequest, "robot_id is empty");
      auto deleted = store_->delete_robot(robot);
      if (!deleted) {
        bump(metrics_.store_errors);
        return reply(id, RequestResult::IoError, deleted.message());
      }
      if (*deleted == 0)
        return reply(id, RequestResult::UnknownRobot, "no stored observations of robot '" + robot + "'");
      metrics_.store_observations.fetch_sub(*deleted, std::memory_order_relaxed);
      return start_rebuild(RebuildTicket{
          RebuildCause::ResetRobot, id, grid_->config(),
          "deleted " + std::to_string(*deleted) + " observations of robot '" + robot + "'", std::nullopt});
    }
  }
  reply(id, RequestResult::InvalidRequest,
        "unknown edit kind " + std::to_string(static_cast<int>(edit.kind)));
}

void Mapper::handle_file(const FileRequest& request) {
  const uint64_t id = request.request_id;
  const std::string& path = request.yaml_path;
  if (request.action == FileAction::Export) {
    const FileOutcome out = export_map_file(*grid_, path);
    return reply(id, file_result(out), out.message);
  }
  if (request.action == FileAction::ExportTrajectoryTum ||
      request.action == FileAction::ExportTrajectoryCarmen) {
    // The open batch is read through the same connection: every observation stored so far is in it
    // (those still waiting for their keyframe's match are not stored yet).
    const FileOutcome out = export_trajectory_file(
        *store_, request.robot_id, path,
        request.action == FileAction::ExportTrajectoryTum ? TrajectoryFormat::Tum : TrajectoryFormat::Carmen);
    return reply(id, file_result(out), out.message);
  }
  if (request.action != FileAction::Import)
    return reply(id, RequestResult::InvalidRequest,
                 "unknown action " + std::to_string(static_cast<int>(request.action)));
  FileOutcome in = read_map_file(path);
  if (!in.ok()) return reply(id, failure_result(in.failure), in.message);
  auto previous = store_->load_prior();
  Status saved = previous ? store_->save_prior(*in.image) : previous.status();
  if (!saved) {
    bump(metrics_.store_errors);
    return reply(id, RequestResult::IoError, saved.message());
  }
  has_prior_ = true;
  start_rebuild(RebuildTicket{RebuildCause::Import, id, grid_->config(), in.message + "; now the map's prior",
                              std::move(*previous)});
}

void Mapper::start_rebuild(RebuildTicket ticket) {
  // The worker reads what is committed; nothing may be pending in this connection's batch.
  Status ready = store_->flush();
  if (ready) ready = worker_.start(ticket.config, options_.store, corrections_);
  if (!ready) {
    bump(metrics_.store_errors);
    if (ticket.cause == RebuildCause::Rerender)
      spdlog::error("cannot re-render: {}", ready.message());
    else
      reply(ticket.request_id, RequestResult::IoError, "cannot rebuild: " + ready.message());
    return;
  }
  spdlog::info("rebuilding the map: {}", ticket.done);
  ticket_ = std::move(ticket);
}

void Mapper::finish_rebuild(RebuildOutcome outcome) {
  if (ticket_->cause == RebuildCause::PartialRerender) return finish_partial(std::move(outcome));
  if (ticket_->cause == RebuildCause::Compaction) return finish_compaction(std::move(outcome));
  RebuildTicket ticket = std::move(*ticket_);
  ticket_.reset();
  if (!outcome.grid) {
    if (ticket.cause == RebuildCause::Import) {  // put the old prior back: the store matches the map again
      Status restored =
          ticket.previous_prior ? store_->save_prior(*ticket.previous_prior) : store_->clear_prior();
      has_prior_ = ticket.previous_prior.has_value();
      if (!restored) spdlog::error("{}", restored.message());
    }
    store_deferred_as_drawn();
    std::string message = "rebuild failed, the map is unchanged: " + outcome.grid.message();
    if (ticket.cause == RebuildCause::ResetRobot) message = ticket.done + "; " + message;
    if (ticket.cause == RebuildCause::Rerender)
      spdlog::error("{}", message);
    else
      reply(ticket.request_id, RequestResult::IoError, message);
    return;
  }
  OccupancyGrid& fresh = *outcome.grid;
  index_ = std::move(outcome.index);  // the fresh grid's; the observations kept aside join it below
  for (const Deferred& d : deferred_) {
    const Pose& correction =
        corrections_.contains(d.keyframe_id) ? corrections_.lookup(d.keyframe_id) : d.map_from_odom;
    const ObservationView odom = d.view();
    const ObservationView view =
        is_identity(correction) ? odom : to_map_frame(correction, odom, hits_, misses_);
    if (auto r = fresh.integrate(view); !r) {
      bump(metrics_.rejected);
      log_.warn("reject:" + d.robot_id, "observation of robot '{}' seq {} rejected by the new layout: {}",
                d.robot_id, d.seq, r.message());
      continue;
    }
    store_observation(d.robot_id, d.seq, d.stamp_ns, d.keyframe_id, odom, d.robot_stamp_ns, correction,
                      box_of(view));
  }
  deferred_.clear();
  if (ticket.cause == RebuildCause::Layout) {
    if (Status s = store_->save_config(ticket.config); !s) {
      bump(metrics_.store_errors);
      log_.warn("store", "{} (the new layout holds until a restart)", s.message());
    }
  }
  const bool same = same_geometry(*grid_, fresh);
  grid_ = std::move(fresh);
  seen_layout_ = grid_->layout_version();
  if (!same) ++layout_id_;
  bump(metrics_.rebuilds);
  if (ticket.cause == RebuildCause::Rerender) {
    bump(metrics_.rerender_observations, outcome.stats.observations);
    last_full_redraw_ns_ = newest_stamp_ns_;  // the fresh index does not know who moved: all may have
  }
  swapped_ = true;

  const RebuildStats& st = outcome.stats;
  std::string message = ticket.done + "; rebuilt " + std::to_string(st.observations) + " observations, " +
                        std::to_string(st.prior_cells) + " prior cells, " + std::to_string(st.obstructions) +
                        " obstructions in " + std::to_string(outcome.took.count()) + " ms (" +
                        std::to_string(grid_->width()) + "x" + std::to_string(grid_->height()) + " cells)";
  if (st.rejected > 0) message += "; " + std::to_string(st.rejected) + " observations rejected";
  if (!st.first_error.empty()) message += "; first problem: " + st.first_error;
  if (ticket.cause == RebuildCause::Rerender)
    spdlog::info("{}", message);
  else
    reply(ticket.request_id, RequestResult::Ok, message);
}

void Mapper::reply(uint64_t request_id, RequestResult result, const std::string& message) {
  if (result == RequestResult::Ok) {
    spdlog::info("request {}: {}", request_id, message);
  } else {
    bump(metrics_.request_errors);
    log_.warn("request", "request {} refused: {}", request_id, message);
  }
  replies_.push_back(RequestReply{request_id, result, message});
}

}  // namespace slam::mapper
