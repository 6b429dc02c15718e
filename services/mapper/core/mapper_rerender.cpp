// Mapper: re-renders after keyframes moved. Planned on the loop from the footprint index; a partial
// one draws its tiles on the worker, then the loop draws the observations it kept aside meanwhile into
// the same tiles, copies them into the grid (the changed tiles go out in the next patch, not a
// snapshot) and records the new corrections in the index (see partial_rerender.hpp).
#include <utility>

#include "mapper/core/mapper.hpp"
#include "mapper/core/partial_rerender.hpp"

namespace slam::mapper {

void Mapper::start_rerender(bool full) {
  std::string why = "requested";
  if (!full) {
    RerenderDecision decision = plan_rerender(index_, corrections_, *grid_, options_.rerender);
    if (decision.kind == RerenderDecision::Kind::Nothing) {
      spdlog::debug("re-render: no keyframe moved by more than {} cells", options_.rerender.min_shift_cells);
      return;
    }
    if (decision.kind == RerenderDecision::Kind::Partial) {
      const RerenderPlan& plan = decision.plan;
      std::string done = "re-render of " + std::to_string(plan.moved) +
                         " moved keyframes: " + std::to_string(plan.tiles.size()) + " tiles, " +
                         std::to_string(plan.replays.size()) + " keyframes replayed";
      // The worker reads what is committed; nothing may be pending in this connection's batch.
      Status ready = store_->flush();
      if (ready) ready = worker_.start_partial(std::move(decision.plan), options_.store);
      if (!ready) {
        bump(metrics_.store_errors);
        spdlog::error("cannot re-render: {}", ready.message());
        return;
      }
      ticket_ =
          RebuildTicket{RebuildCause::PartialRerender, 0, grid_->config(), std::move(done), std::nullopt};
      return;
    }
    why = decision.reason;
  }
  start_rebuild(RebuildTicket{RebuildCause::Rerender, 0, grid_->config(),
                              "re-render with " + std::to_string(corrections_.size()) +
                                  " keyframe corrections (a full one: " + why + ")",
                              std::nullopt});
}

void Mapper::finish_partial(RebuildOutcome outcome) {
  const RebuildTicket ticket = std::move(*ticket_);
  ticket_.reset();
  if (!outcome.partial || !*outcome.partial) {
    store_deferred_as_drawn();
    spdlog::error("re-render failed, the map is unchanged: {}",
                  outcome.partial ? outcome.partial->message() : outcome.grid.message());
    return;
  }
  TileRender& render = **outcome.partial;
  if (render.outside_grid || grid_->layout_version() != render.plan.layout_version) {
    // Drawn where it was (the index agrees); the full re-render that follows draws everything anew.
    store_deferred_as_drawn();
    spdlog::info(
        "{}: {}; a full re-render follows", ticket.done,
        render.outside_grid ? "an observation would lie beyond the grid" : "the grid grew meanwhile");
    rerender_waiting_ = true;
    full_rerender_waiting_ = true;
    return;
  }
  // The observations kept aside are in the live grid already, drawn with their own corrections; the
  // redrawn tiles get them too, after everything the worker replayed (insertion order).
  for (const Deferred& d : deferred_) {
    const ObservationView odom = d.view();
    (void)render.canvas.integrate(
        is_identity(d.map_from_odom) ? odom : to_map_frame(d.map_from_odom, odom, hits_, misses_));
  }
  grid_->redraw(render.canvas);
  record_redraw(render, index_, newest_stamp_ns_);
  store_deferred_as_drawn();
  bump(metrics_.rerenders_partial);
  bump(metrics_.rerender_observations, render.replayed);
  spdlog::info("{}; redrew {} observations ({} rows read) in {} ms", ticket.done, render.replayed,
               render.rows_read, outcome.took.count());
}

void Mapper::store_deferred_as_drawn() {
  for (const Deferred& d : deferred_) {
    const ObservationView odom = d.view();
    const ObservationView view =
        is_identity(d.map_from_odom) ? odom : to_map_frame(d.map_from_odom, odom, hits_, misses_);
    store_observation(d.robot_id, d.seq, d.stamp_ns, d.keyframe_id, odom, d.robot_stamp_ns, d.map_from_odom,
                      box_of(view));
  }
  deferred_.clear();
}

}  // namespace slam::mapper
