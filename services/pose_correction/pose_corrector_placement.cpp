// Global localisation for PoseCorrector: a robot joining a map others have built is searched for on
// the whole map before anything of it is drawn (CorrectorOptions::global_localisation), and so is a
// placed robot found lost (CorrectorOptions::lost_after_unmatched).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "common/core/cell_class.hpp"
#include "pose_correction/free_space_check.hpp"
#include "pose_correction/pose_corrector.hpp"

namespace slam::correction {
namespace {

// The occupied part of `grid` (cells of a wall or an obstruction), with a margin: what a keyframe
// can be placed against. Empty when nothing is occupied.
CellBox occupied_box(const GridView& grid, int32_t margin) {
  const GridGeometry& g = grid.geometry;
  int32_t x0 = g.width, y0 = g.height, x1 = -1, y1 = -1;
  for (int32_t y = 0; y < g.height; ++y) {
    const uint8_t* row = grid.classes.data() + static_cast<size_t>(y) * static_cast<size_t>(g.width);
    for (int32_t x = 0; x < g.width; ++x) {
      if (!is_wall(row[x])) continue;
      x0 = std::min(x0, x);
      x1 = std::max(x1, x);
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
    }
  }
  if (x1 < 0) return {};
  x0 = std::max(0, x0 - margin);
  y0 = std::max(0, y0 - margin);
  x1 = std::min(g.width - 1, x1 + margin);
  y1 = std::min(g.height - 1, y1 + margin);
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

// The rays of the newest keyframe of `held` and of those before it in its segment within
// `trail_m` of travel, in the newest one's frame (by odometry, which holds over a few metres),
// evenly thinned to at most `max_rays`: one sparse keyframe (a v1 robot's 16 points a message)
// fits many places of a building, a few metres of them fit one. Each ray starts at its keyframe's
// origin (the robot moves a few decimetres within one).
void gather_trail(std::span<const Keyframe> held, double trail_m, size_t max_rays, std::vector<Ray>& trail) {
  trail.clear();
  const Keyframe& newest = held.back();
  const Pose to_newest = newest.odom.inverse();
  double travelled = 0.0;
  for (size_t i = held.size(); i-- > 0;) {
    const Keyframe& k = held[i];
    if (k.segment != newest.segment) break;
    if (i + 1 < held.size()) travelled += distance(k.odom.position(), held[i + 1].odom.position());
    if (travelled > trail_m) break;
    const Pose into_newest = to_newest.compose(k.odom);
    const Vec2 origin = into_newest.position();
    for (const Vec2& p : k.points) trail.push_back({origin, into_newest.transform(p)});
  }
  thin_evenly(trail, max_rays);
}

// Map a correction found for `keyframe` (its origin at `pose`) gives its robot's odometry frame.
Pose frame_of(const Pose& pose, const Keyframe& keyframe) {
  return pose.compose(keyframe.odom.inverse());
}

}  // namespace

void PoseCorrector::prepare_placement_map(const GridView& grid) {
  placement_map_ready_ = false;
  const GridGeometry& g = grid.geometry;
  if (g.cells() == 0 || grid.classes.size() != g.cells()) return;
  const CellBox box = occupied_box(grid, 4);
  if (box.empty()) return;
  // Coarser cells (each the occupancy of a square of grid cells) until the map fits the budget.
  int32_t factor = 1;
  while (box.cells() / static_cast<size_t>(factor * factor) > options_.placement_max_map_cells) factor *= 2;
  GridGeometry coarse;
  coarse.resolution = g.resolution * factor;
  coarse.origin = g.corner({box.x0, box.y0});
  coarse.width = (box.width + factor - 1) / factor;
  coarse.height = (box.height + factor - 1) / factor;
  placement_cells_.assign(coarse.cells(), kCellFree);
  for (int32_t y = 0; y < box.height; ++y) {
    const uint8_t* row = grid.classes.data() + g.index({box.x0, box.y0 + y});
    for (int32_t x = 0; x < box.width; ++x)
      if (is_wall(row[x])) placement_cells_[coarse.index({x / factor, y / factor})] = kCellOccupied;
  }
  placement_map_ready_ = static_cast<bool>(placement_search_.set_map(GridView{coarse, placement_cells_}));
}

bool PoseCorrector::give_up_placement(Robot& rb, int64_t now_ns, std::vector<KeyframeCorrection>& out) {
  if (rb.held.empty()) return false;
  if (rb.lost || options_.localise_only) {
    // Its odometry is what failed (or, on a fixed map, its odometry's frame is no place at all): it
    // is searched for as long as it takes, and only its latest keyframes wait.
    const size_t keep = static_cast<size_t>(std::max(1, options_.placement_max_keyframes));
    if (rb.held.size() <= keep) return false;
    const auto drop = static_cast<std::ptrdiff_t>(rb.held.size() - keep);
    for (auto it = rb.held.begin(); it != rb.held.begin() + drop; ++it)
      out.push_back(KeyframeCorrection{it->id, rb.name, it->segment, it->odom, rb.state.map_from_odom, true});
    rb.held.erase(rb.held.begin(), rb.held.begin() + drop);
    stats_.lost_keyframes_dropped += drop;
    return false;
  }
  const double waited_s = static_cast<double>(now_ns - rb.held.front().first_stamp_ns) * 1e-9;
  if (static_cast<int>(rb.held.size()) < options_.placement_max_keyframes &&
      waited_s <= options_.placement_max_wait_s)
    return false;
  ++stats_.placements_given_up;
  spdlog::warn(
      "pose correction: robot {} not found on the map in {} keyframes, {:.0f} s: placed where its "
      "odometry says",
      rb.name, rb.held.size(), waited_s);
  place(rb, std::nullopt, 0.0);
  return true;
}

void PoseCorrector::search_placement(Robot& rb, const GridView& grid, int64_t now_ns,
                                     std::vector<KeyframeCorrection>& out) {
  if (rb.held.empty() || give_up_placement(rb, now_ns, out)) return;
  const Keyframe& keyframe = rb.held.back();
  if (!rb.hypothesis && rb.searched_at &&
      distance(*rb.searched_at, keyframe.odom.position()) < options_.placement_search_travel_m)
    return;
  if (!placement_map_ready_ || now_ns - placement_map_ns_ > kPlacementMapAge_ns) {
    prepare_placement_map(grid);
    placement_map_ns_ = now_ns;
  }
  if (!placement_map_ready_) return;  // nothing on the map yet: it waits for the others' (or the wait's end)
  gather_trail(rb.held, options_.placement_trail_m, options_.placement_max_points, placement_rays_);
  placement_points_.clear();
  for (const Ray& r : placement_rays_) placement_points_.push_back(r.end);

  // No hypothesis: the whole map at every heading. A hypothesis: around where it puts this keyframe.
  const GridGeometry& map = placement_search_.geometry();
  SearchRegion region;
  if (rb.hypothesis) {
    region = {rb.hypothesis->compose(keyframe.odom), options_.placement_agree_m,
              options_.placement_agree_rad};
  } else {
    const double half_width = 0.5 * map.width * map.resolution,
                 half_height = 0.5 * map.height * map.resolution;
    region = {{map.origin.x + half_width, map.origin.y + half_height, 0.0},
              std::max(half_width, half_height),
              2.0 * std::numbers::pi};
  }
  ++stats_.placement_searches;
  rb.searched_at = keyframe.odom.position();
  const auto found = placement_search_.search(placement_points_, region);
  // The walls are traced only for a match that passes the cheaper tests.
  const bool good = found && found->score >= options_.placement_min_score &&
                    (rb.hypothesis || found->ambiguity() <= options_.placement_max_ambiguity) &&
                    crossed_wall_share(GridView{map, placement_cells_}, found->pose, placement_rays_,
                                       kWallCrossingMargin_m) <= options_.placement_max_crossed_walls;
  rb.state.localisation_score = found ? found->score * (1.0 - found->ambiguity()) : 0.0;
  if (good) {
    const Pose frame = frame_of(found->pose, keyframe);
    rb.hypothesis = frame;
    ++rb.confirmations;
  } else if (rb.hypothesis) {
    ++stats_.placement_contradicted;
    spdlog::info(
        "pose correction: robot {}: keyframe {} disagrees with where it was thought to be; searching again",
        rb.name, keyframe.id);
    rb.hypothesis.reset();
    rb.confirmations = 0;
  }
  const Placement state = rb.hypothesis ? Placement::Placing
                          : rb.lost     ? Placement::Lost
                                        : Placement::Unplaced;
  if (state != rb.state.placement) {
    rb.state.placement = state;
    mark_changed(rb, rb.state.source);
  }
  if (rb.hypothesis && rb.confirmations >= options_.placement_confirmations) {
    ++stats_.robots_placed;
    place(rb, rb.hypothesis, rb.state.localisation_score);
  }
}

void PoseCorrector::place(Robot& rb, std::optional<Pose> map_from_odom, double score) {
  if (map_from_odom) {
    rb.state.map_from_odom = *map_from_odom;
    spdlog::info(
        "pose correction: robot {} found on the map{} (score {:.2f}): its odometry origin is at "
        "({:.2f}, {:.2f}, {:.1f} deg)",
        rb.name, rb.lost ? " again" : "", score, map_from_odom->x, map_from_odom->y,
        to_degrees(map_from_odom->theta));
  }
  rb.lost = false;
  rb.state.placement = Placement::Placed;
  rb.state.localisation_score = score;
  rb.hypothesis.reset();
  rb.confirmations = 0;
  rb.searched_at.reset();
  // The waiting keyframes go the usual way now, oldest first, predicted from the placement.
  for (Keyframe& keyframe : rb.held) closed_.push_back(std::move(keyframe));
  rb.held.clear();
  mark_changed(rb, map_from_odom ? CorrectionSource::Match : rb.state.source);
}

void PoseCorrector::watch_tracking(const MatchJob& job, Robot& rb) {
  if (options_.lost_after_unmatched <= 0 || rb.state.placement != Placement::Placed) return;
  if (job.narrow) {
    rb.unmatched_in_row = 0;
    if (!job.keyframe.scans) return;  // a sparse keyframe's score says little (see the options)
    const auto window = static_cast<size_t>(std::clamp(options_.lost_window, 1, 64));
    if (rb.track_scores.size() < window) {
      rb.track_scores.push_back(job.narrow->score);
    } else {
      rb.track_scores[rb.track_score_next] = job.narrow->score;
    }
    rb.track_score_next = (rb.track_score_next + 1) % window;
    double sum = 0.0;
    for (double s : rb.track_scores) sum += s;
    if (rb.track_scores.size() == window && sum <= options_.lost_mean_score * static_cast<double>(window))
      mark_lost(rb, fmt::format("its last {} keyframes matched at {:.2f} on average", window,
                                sum / static_cast<double>(window)));
  } else if (job.track && !job.standing &&
             job.keyframe.points.size() >= static_cast<size_t>(options_.matcher.min_points) &&
             ++rb.unmatched_in_row >= options_.lost_after_unmatched) {
    mark_lost(rb, fmt::format("its last {} keyframes matched nowhere near", rb.unmatched_in_row));
  }
}

void PoseCorrector::mark_lost(Robot& rb, const std::string& why) {
  ++stats_.robots_lost;
  spdlog::warn(
      "pose correction: robot {} lost: {} (carried, or its odometry broke?); searching for it on the whole "
      "map, drawing nothing meanwhile",
      rb.name, why);
  rb.lost = true;
  rb.unmatched_in_row = 0;
  rb.track_scores.clear();
  rb.track_score_next = 0;
  rb.state.placement = Placement::Lost;
  rb.state.localisation_score = 0.0;
  // Its next keyframes start a chain of their own: no odometry edge joins them to where it was lost.
  rb.last_node.reset();
  rb.recent_nodes.clear();
  rb.last_tied.reset();
  rb.relocalise_hypothesis.reset();
  rb.relocalise_agreed = 0;
  rb.hypothesis.reset();
  rb.confirmations = 0;
  rb.searched_at.reset();
  mark_changed(rb, rb.state.source);
}

}  // namespace slam::correction
