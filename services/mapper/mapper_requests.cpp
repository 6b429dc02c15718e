// MapperNode's requests: grid layout changes, edits, map files, and the rebuilds some of them start.
// Every request gets one MapReply; a refused request leaves the map and the store as they were.
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "mapper/map_files.hpp"
#include "mapper/mapper_msgs.hpp"
#include "mapper/mapper_node.hpp"

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

}  // namespace

void MapperNode::run_queued_commands() {
  while (!worker_.busy() && !queued_.empty()) {
    MapCommand command = std::move(queued_.front());
    queued_.pop_front();
    handle(command);
  }
}

void MapperNode::handle(const MapCommand& command) {
  bump(metrics_.requests);
  std::visit(
      [this](const auto& c) {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, slam::GridConfig>)
          handle_config(c);
        else if constexpr (std::is_same_v<T, slam::MapEdit>)
          handle_edit(c);
        else
          handle_file(c);
      },
      command);
}

void MapperNode::handle_config(const slam::GridConfig& request) {
  auto config = requested_config(request, grid_->config());
  if (!config) {
    reply(request.request_id(), slam::MAP_INVALID_REQUEST, "grid config refused: " + config.message());
    return;
  }
  if (same_layout(*config, grid_->config())) {
    reply(request.request_id(), slam::MAP_OK, "grid layout unchanged (" + layout_text(*config) + ")");
    return;
  }
  start_rebuild(RebuildTicket{RebuildCause::Layout, request.request_id(), *config,
                              "grid layout changed to " + layout_text(*config), std::nullopt});
}

void MapperNode::handle_edit(const slam::MapEdit& edit) {
  const uint64_t id = edit.request_id();
  const double x = edit.point().x();
  const double y = edit.point().y();
  switch (edit.kind()) {
    case slam::EDIT_OBSTRUCT: {
      const auto cell = grid_->cell_at({x, y});
      const bool already = cell && (grid_->cell_class(cell->x, cell->y) & kCellObstructed) != 0;
      if (Status s = grid_->obstruct(x, y); !s) return reply(id, slam::MAP_INVALID_REQUEST, s.message());
      if (already)
        return reply(id, slam::MAP_OK, "the cell at " + point_text(x, y) + " is already obstructed");
      if (Status s = store_->add_obstruction({x, y}); !s) {
        (void)grid_->unobstruct(x, y);
        bump(metrics_.store_errors);
        return reply(id, slam::MAP_IO_ERROR, s.message());
      }
      return reply(id, slam::MAP_OK, "obstructed the cell at " + point_text(x, y));
    }
    case slam::EDIT_UNOBSTRUCT: {
      if (!std::isfinite(x) || !std::isfinite(y))
        return reply(id, slam::MAP_INVALID_REQUEST, "point is not finite");
      const std::vector<Vec2> removed = grid_->unobstruct(x, y);
      for (const Vec2& p : removed) {
        if (Status s = store_->remove_obstruction(p); !s) {
          bump(metrics_.store_errors);
          return reply(id, slam::MAP_IO_ERROR,
                       s.message() + " (the map no longer shows it; a restart would)");
        }
      }
      return reply(id, slam::MAP_OK,
                   removed.empty() ? "no manual obstruction at " + point_text(x, y)
                                   : "removed " + std::to_string(removed.size()) + " obstruction(s) at " +
                                         point_text(x, y));
    }
    case slam::EDIT_CLEAR_OBSTRUCTIONS: {
      if (Status s = store_->clear_obstructions(); !s) {
        bump(metrics_.store_errors);
        return reply(id, slam::MAP_IO_ERROR, s.message());
      }
      const size_t count = grid_->obstructions().size();
      grid_->clear_obstructions();
      return reply(id, slam::MAP_OK, "cleared " + std::to_string(count) + " manual obstruction(s)");
    }
    case slam::EDIT_RESET_ROBOT: {
      const std::string robot = edit.robot_id().to_string();
      if (robot.empty()) return reply(id, slam::MAP_INVALID_REQUEST, "robot_id is empty");
      auto deleted = store_->delete_robot(robot);
      if (!deleted) {
        bump(metrics_.store_errors);
        return reply(id, slam::MAP_IO_ERROR, deleted.message());
      }
      if (*deleted == 0)
        return reply(id, slam::MAP_UNKNOWN_ROBOT, "no stored observations of robot '" + robot + "'");
      metrics_.store_observations.fetch_sub(*deleted, std::memory_order_relaxed);
      return start_rebuild(RebuildTicket{
          RebuildCause::ResetRobot, id, grid_->config(),
          "deleted " + std::to_string(*deleted) + " observations of robot '" + robot + "'", std::nullopt});
    }
  }
  reply(id, slam::MAP_INVALID_REQUEST, "unknown edit kind " + std::to_string(static_cast<int>(edit.kind())));
}

void MapperNode::handle_file(const slam::MapFileRequest& request) {
  const uint64_t id = request.request_id();
  const std::string path = request.yaml_path().to_string();
  if (request.action() == slam::MAP_EXPORT) {
    const FileOutcome out = export_map_file(*grid_, path);
    return reply(id, to_map_result(out.failure), out.message);
  }
  if (request.action() != slam::MAP_IMPORT)
    return reply(id, slam::MAP_INVALID_REQUEST,
                 "unknown action " + std::to_string(static_cast<int>(request.action())));
  FileOutcome in = read_map_file(path);
  if (!in.ok()) return reply(id, to_map_result(in.failure), in.message);
  auto previous = store_->load_prior();
  Status saved = previous ? store_->save_prior(*in.image) : previous.status();
  if (!saved) {
    bump(metrics_.store_errors);
    return reply(id, slam::MAP_IO_ERROR, saved.message());
  }
  start_rebuild(RebuildTicket{RebuildCause::Import, id, grid_->config(), in.message + "; now the map's prior",
                              std::move(*previous)});
}

void MapperNode::start_rebuild(RebuildTicket ticket) {
  // The worker reads what is committed; nothing may be pending in this connection's batch.
  Status ready = store_->flush();
  if (ready) ready = worker_.start(ticket.config, options_.store);
  if (!ready) {
    bump(metrics_.store_errors);
    reply(ticket.request_id, slam::MAP_IO_ERROR, "cannot rebuild: " + ready.message());
    return;
  }
  spdlog::info("rebuilding the map: {}", ticket.done);
  ticket_ = std::move(ticket);
}

void MapperNode::finish_rebuild(RebuildOutcome outcome) {
  RebuildTicket ticket = std::move(*ticket_);
  ticket_.reset();
  if (!outcome.grid) {
    if (ticket.cause == RebuildCause::Import) {  // put the old prior back: the store matches the map again
      Status restored =
          ticket.previous_prior ? store_->save_prior(*ticket.previous_prior) : store_->clear_prior();
      if (!restored) spdlog::error("{}", restored.message());
    }
    for (const Deferred& d : deferred_) store_observation(d.robot_id, d.seq, d.stamp_ns, d.view());
    deferred_.clear();
    std::string message = "rebuild failed, the map is unchanged: " + outcome.grid.message();
    if (ticket.cause == RebuildCause::ResetRobot) message = ticket.done + "; " + message;
    reply(ticket.request_id, slam::MAP_IO_ERROR, message);
    return;
  }
  OccupancyGrid& fresh = *outcome.grid;
  for (const Deferred& d : deferred_) {
    if (auto r = fresh.integrate(d.view()); !r) {
      bump(metrics_.rejected);
      warn("reject:" + d.robot_id, "observation of robot '" + d.robot_id + "' seq " + std::to_string(d.seq) +
                                       " rejected by the new layout: " + r.message());
      continue;
    }
    store_observation(d.robot_id, d.seq, d.stamp_ns, d.view());
  }
  deferred_.clear();
  if (ticket.cause == RebuildCause::Layout) {
    if (Status s = store_->save_config(ticket.config); !s) {
      bump(metrics_.store_errors);
      warn("store", s.message() + " (the new layout holds until a restart)");
    }
  }
  const bool same = same_geometry(*grid_, fresh);
  grid_ = std::move(fresh);
  seen_layout_ = grid_->layout_version();
  if (!same) ++layout_id_;
  bump(metrics_.rebuilds);
  publish_snapshot(true);

  const RebuildStats& st = outcome.stats;
  std::string message = ticket.done + "; rebuilt " + std::to_string(st.observations) + " observations, " +
                        std::to_string(st.prior_cells) + " prior cells, " + std::to_string(st.obstructions) +
                        " obstructions in " + std::to_string(outcome.took.count()) + " ms (" +
                        std::to_string(grid_->width()) + "x" + std::to_string(grid_->height()) + " cells)";
  if (st.rejected > 0) message += "; " + std::to_string(st.rejected) + " observations rejected";
  if (!st.first_error.empty()) message += "; first problem: " + st.first_error;
  reply(ticket.request_id, slam::MAP_OK, message);
}

void MapperNode::reply(uint64_t request_id, slam::MapResult result, const std::string& message) {
  if (result == slam::MAP_OK) {
    spdlog::info("request {}: {}", request_id, message);
  } else {
    bump(metrics_.request_errors);
    warn("request", "request " + std::to_string(request_id) + " refused: " + message);
  }
  slam::MapReply r;
  r.request_id(request_id);
  r.result(result);
  r.message(message.substr(0, 511));  // string<512>
  if (!reply_writer_->write(r)) bump(metrics_.write_failures);
}

}  // namespace slam::mapper
