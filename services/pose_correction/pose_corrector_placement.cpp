// Global localisation for PoseCorrector: a robot joining a map others have built is searched for on
// the whole map before anything of it is drawn (CorrectorOptions::global_localisation), and so is a
// placed robot found lost (CorrectorOptions::lost_after_unmatched).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "pose_correction/free_space_check.hpp"
#include "pose_correction/pose_corrector.hpp"

namespace slam::correction {
namespace {

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

// Map a correction found for a keyframe (its origin at `pose`, at `odom` in its odometry) gives its
// robot's odometry frame.
Pose frame_of(const Pose& pose, const Pose& odom) {
  return pose.compose(odom.inverse());
}

}  // namespace

void PoseCorrector::trim_held(Robot& rb, std::vector<KeyframeCorrection>& out) {
  // Where the robot is, is unknown: its keyframes are never drawn where its odometry says (that is
  // what pasted robots switched on elsewhere onto the first one's map). It is searched for as long
  // as it takes, and only its latest keyframes wait; older ones go with their observations.
  const size_t keep = static_cast<size_t>(std::max(1, options_.placement_max_keyframes));
  if (rb.held.size() <= keep) return;
  const auto drop = static_cast<std::ptrdiff_t>(rb.held.size() - keep);
  for (auto it = rb.held.begin(); it != rb.held.begin() + drop; ++it)
    out.push_back(KeyframeCorrection{it->id, rb.name, it->segment, it->odom, rb.state.map_from_odom, true});
  rb.held.erase(rb.held.begin(), rb.held.begin() + drop);
  stats_.unplaced_keyframes_dropped += drop;
}

void PoseCorrector::search_placements(const GridView& grid, int64_t now_ns) {
  const auto robots = static_cast<uint32_t>(robots_.size());
  for (uint32_t k = 0; k < robots; ++k) {
    const uint32_t r = (placement_turn_ + k) % robots;
    const Robot& rb = robots_[r];
    if (rb.state.placement == Placement::Placed || rb.held.empty() ||
        (rb.held.back().id == rb.looked_at && !search_again(rb, now_ns)))
      continue;
    if (placement_in_flight_) {
      placement_turn_ = r;
      return;
    }
    search_placement(r, grid, now_ns);
  }
}

void PoseCorrector::search_placement(uint32_t robot, const GridView& grid, int64_t now_ns) {
  Robot& rb = robots_[robot];
  const Keyframe& keyframe = rb.held.back();
  rb.looked_at = keyframe.id;
  if (!rb.hypothesis && rb.searched_at &&
      distance(*rb.searched_at, keyframe.odom.position()) < search_travel_m(rb) && !search_again(rb, now_ns))
    return;
  std::unique_ptr<PlacementJob> job =
      placement_job_ ? std::move(placement_job_) : std::make_unique<PlacementJob>();
  job->robot = robot;
  job->generation = rb.generation;
  job->keyframe_odom = keyframe.odom;
  job->hypothesis = rb.hypothesis;
  gather_trail(rb.held, options_.placement_trail_m, options_.placement_max_points, job->rays);
  // The searched map is rebuilt from a copy of the grid every so often (and while it holds no wall).
  job->new_map = !placement_map_ready_ || now_ns - placement_map_ns_ > kPlacementMapAge_ns;
  if (job->new_map) {
    job->grid_geometry = grid.geometry;
    job->grid_cells.assign(grid.classes.begin(), grid.classes.end());
    placement_map_ns_ = now_ns;
  }
  rb.searched_at = keyframe.odom.position();
  rb.searched_ns = now_ns;
  if (placement_thread_) {
    placement_in_flight_ = true;
    placement_thread_->submit(std::move(job));
    return;
  }
  placement_searcher_.run(*job);
  apply_placement(*job);
  placement_job_ = std::move(job);
}

void PoseCorrector::land_placement() {
  if (!placement_thread_) return;
  landed_placements_.clear();
  placement_thread_->take_done(landed_placements_);
  for (auto& job : landed_placements_) {
    placement_in_flight_ = false;
    apply_placement(*job);
    placement_job_ = std::move(job);
  }
  landed_placements_.clear();
}

void PoseCorrector::apply_placement(const PlacementJob& job) {
  placement_map_ready_ = job.map_ready;
  Robot& rb = robots_[job.robot];
  if (!job.map_ready) {  // nothing on the map yet: it waits for the others' (or the wait's end)
    rb.searched_at.reset();
    return;
  }
  // Reset, placed (an operator, the wait's end) or its hypothesis dropped while it was searched for.
  if (job.generation != rb.generation || rb.state.placement == Placement::Placed ||
      job.hypothesis.has_value() != rb.hypothesis.has_value())
    return;
  ++stats_.placement_searches;
  const auto& found = job.found;
  rb.state.localisation_score = found ? found->score * (1.0 - found->ambiguity()) : 0.0;
  const bool refused =
      job.passes && rejected(rb, frame_of(found->pose, job.keyframe_odom), job.keyframe_odom);
  if (refused) ++stats_.placements_refused;
  if (!job.hypothesis) rb.searches_unfound = job.passes && !refused ? 0 : rb.searches_unfound + 1;
  if (job.passes && !refused) {
    rb.hypothesis = frame_of(found->pose, job.keyframe_odom);
    ++rb.confirmations;
  } else if (rb.hypothesis) {
    ++stats_.placement_contradicted;
    spdlog::info(
        "pose correction: robot {}: a keyframe disagrees with where it was thought to be; searching again",
        rb.name);
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

bool PoseCorrector::rejected(const Robot& rb, const Pose& frame, const Pose& odom) const {
  const Pose at = frame.compose(odom);
  return std::ranges::any_of(rb.rejected, [&](const Pose& r) {
    const Pose there = r.compose(odom);
    return distance(there.position(), at.position()) <= options_.placement_agree_m &&
           std::abs(wrap_angle(there.theta - at.theta)) <= options_.placement_agree_rad;
  });
}

Status PoseCorrector::answer_placement(std::string_view robot, bool accept) {
  const auto it = robot_ids_.find(std::string(robot));
  if (it == robot_ids_.end()) {
    ++stats_.rejected_inputs;
    return Error{"unknown robot '" + std::string(robot) + "': no observation from it yet"};
  }
  Robot& rb = robots_[it->second];
  if (accept) {
    if (!rb.hypothesis) {
      ++stats_.rejected_inputs;
      return Error{fmt::format("robot {} is {}: nothing to accept (give it a pose: slamctl pose)", rb.name,
                               rb.state.placement == Placement::Placed ? "placed already" : "not found yet")};
    }
    spdlog::info("pose correction: robot {}: an operator accepted where it was found", rb.name);
    ++stats_.robots_placed;
    place(rb, rb.hypothesis, rb.state.localisation_score);
    return Status::ok();
  }
  std::optional<Pose> wrong = rb.hypothesis;
  if (!wrong && rb.state.placement == Placement::Placed) wrong = rb.state.map_from_odom;
  if (!wrong) {
    ++stats_.rejected_inputs;
    return Error{fmt::format("robot {} is not placed nor being placed: nothing to reject", rb.name)};
  }
  if (rb.rejected.size() >= options_.placement_max_rejected) rb.rejected.erase(rb.rejected.begin());
  rb.rejected.push_back(*wrong);
  if (rb.hypothesis) {
    spdlog::info("pose correction: robot {}: an operator rejected where it was being placed; searching on",
                 rb.name);
    rb.hypothesis.reset();
    rb.confirmations = 0;
    rb.searched_at.reset();
    rb.state.placement = rb.lost ? Placement::Lost : Placement::Unplaced;
    mark_changed(rb, rb.state.source);
  } else {
    mark_lost(rb, "an operator rejected where it was placed");
  }
  return Status::ok();
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
  rb.searches_unfound = 0;
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
  rb.searches_unfound = 0;
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
