// The matching side of PoseCorrector: what each keyframe is matched against (a window of the grid
// for tracking, a local grid drawn from old keyframes for the tie to the map), prepared on the map
// thread, and the match itself, run on the match worker.
#include <algorithm>
#include <cmath>
#include <utility>

#include "pose_correction/gaussian_pose.hpp"
#include "pose_correction/pose_corrector.hpp"

namespace slam::correction {

namespace {

// Beyond a keyframe's farthest point: the keyframes around it that see what it sees.
constexpr double kLocalReachMargin_m = 0.5;

}  // namespace

void PoseCorrector::old_neighbours(uint32_t robot, int64_t stamp_ns, Vec2 centre, double radius,
                                   std::vector<uint32_t>& out) {
  out.clear();
  index_.near(centre, radius, out);
  const auto min_age_ns = static_cast<int64_t>(options_.old_age_s * 1e9);
  std::erase_if(out, [&](uint32_t slot) {
    const Node& n = nodes_[slot];
    const bool old = n.robot != robot || stamp_ns - n.stamp_ns >= min_age_ns;
    return !old || n.points.empty() || distance(n.estimate.position(), centre) > radius;
  });
  std::sort(out.begin(), out.end(), [&](uint32_t a, uint32_t b) {
    return distance(nodes_[a].estimate.position(), centre) < distance(nodes_[b].estimate.position(), centre);
  });
  if (out.size() > options_.tie_max_keyframes) out.resize(options_.tie_max_keyframes);
}

void PoseCorrector::gather_recent_trail(const Robot& rb, const Keyframe& keyframe, const Pose& pose,
                                        std::vector<Ray>& out) {
  out.clear();
  for (const Vec2& p : keyframe.points) out.push_back({{0.0, 0.0}, p});
  const Pose keyframe_from_map = pose.inverse();
  Vec2 later_odom = keyframe.odom.position();
  double travel = 0.0;
  for (auto it = rb.recent_nodes.rbegin(); it != rb.recent_nodes.rend(); ++it) {
    const Node& n = nodes_[*it];
    if (n.removed || n.segment != keyframe.segment) break;
    travel += distance(n.odom.position(), later_odom);
    if (travel > options_.placement_trail_m) break;
    later_odom = n.odom.position();
    const Pose keyframe_from_node = keyframe_from_map.compose(n.estimate);
    const Vec2 origin = keyframe_from_node.position();
    for (const Vec2& p : n.points) out.push_back({origin, keyframe_from_node.transform(p)});
  }
  thin_evenly(out, options_.placement_max_points);
}

void PoseCorrector::prepare_relocalisation(const Robot& rb, const Keyframe& keyframe, MatchJob& job) {
  Pose centre = job.predicted;
  double linear =
      std::min(3.0 * std::sqrt(std::max(rb.pose_cov(0, 0), rb.pose_cov(1, 1))), options_.relocalise_max_m);
  double angular = std::min(3.0 * std::sqrt(rb.pose_cov(2, 2)), options_.relocalise_max_rad);
  job.relocalise_confirming = rb.relocalise_hypothesis.has_value();
  if (job.relocalise_confirming) {
    centre = rb.relocalise_hypothesis->compose(keyframe.odom);
    linear = options_.placement_agree_m;
    angular = options_.placement_agree_rad;
  }
  old_neighbours(keyframe.robot, keyframe.first_stamp_ns, centre.position(),
                 linear + options_.closure_radius_m, neighbours_);
  if (static_cast<int>(neighbours_.size()) < options_.closure_min_keyframes) return;
  // The trail is drawn about the prediction, where the robot's own recent keyframes hold it.
  gather_recent_trail(rb, keyframe, job.predicted, job.relocalise_rays);
  job.relocalise_points.clear();
  double reach = 0.0;
  for (const Ray& r : job.relocalise_rays) {
    job.relocalise_points.push_back(r.end);
    reach = std::max(reach, norm(r.end));
  }
  reach = std::min(reach, job.recovery_search.options().max_point_range_m);
  const double half = linear + reach + options_.window_margin_m;
  job.relocalise_geometry =
      draw_local_grid(neighbours_, centre.position(), half, kRelocaliseResolution_m, job.relocalise_cells);
  job.relocalise_region = {centre, linear, angular};
  job.relocalise_anchor = neighbours_.front();
  job.relocalise = true;
  ++stats_.trail_searches;
}

void PoseCorrector::search_relocalisation(ScanMatcher& matcher, MatchJob& job) const {
  const GridView view{job.relocalise_geometry, job.relocalise_cells};
  if (!job.recovery_search.set_map(view)) return;
  const auto found = job.recovery_search.search(job.relocalise_points, job.relocalise_region);
  if (!found || found->score < options_.placement_min_score ||
      (!job.relocalise_confirming && found->ambiguity() > options_.placement_max_ambiguity))
    return;
  // A look-alike place fits the points but its rays run through the old keyframes' walls.
  if (crossed_wall_share(view, found->pose, job.relocalise_rays, kWallCrossingMargin_m) >
      options_.relocalise_max_crossed_walls)
    return;
  // The lattice's best is whole cells and heading steps: refined by the tracking search around it.
  if (auto refined = matcher.match(view, job.relocalise_points, found->pose, options_.track_window,
                                   options_.scan_independent_points))
    job.relocalised = *refined;
}

GridGeometry PoseCorrector::draw_local_grid(std::span<const uint32_t> slots, Vec2 centre, double half_extent,
                                            double resolution, std::vector<uint8_t>& cells) const {
  GridGeometry g;
  g.resolution = resolution;
  g.width = g.height = static_cast<int32_t>(std::ceil(2.0 * half_extent / resolution));
  g.origin = {centre.x - half_extent, centre.y - half_extent};
  cells.assign(g.cells(), 0);
  for (uint32_t slot : slots) {
    const Node& n = nodes_[slot];
    for (const Vec2& p : n.points) {
      if (const auto c = g.cell_at(n.estimate.transform(p))) cells[g.index(*c)] = 2;  // occupied
    }
  }
  return g;
}

void PoseCorrector::window_points(Vec2 centre, double reach, double half_extent, std::vector<Vec2>& out) {
  // Keyframes within a sensor's reach of the keyframe's origin see what it sees; a fixed radius
  // keeps the candidates bounded by the map's density, not its size.
  neighbours_.clear();
  index_.near(centre, reach, neighbours_);
  std::erase_if(neighbours_,
                [&](uint32_t slot) { return nodes_[slot].removed || nodes_[slot].points.empty(); });
  if (neighbours_.size() > options_.refine_max_keyframes) {
    std::nth_element(neighbours_.begin(),
                     neighbours_.begin() + static_cast<std::ptrdiff_t>(options_.refine_max_keyframes),
                     neighbours_.end(), [&](uint32_t a, uint32_t b) {
                       return distance(nodes_[a].estimate.position(), centre) <
                              distance(nodes_[b].estimate.position(), centre);
                     });
    neighbours_.resize(options_.refine_max_keyframes);
  }
  gather_points(neighbours_, centre, half_extent, out);
}

void PoseCorrector::gather_points(std::span<const uint32_t> slots, Vec2 centre, double half_extent,
                                  std::vector<Vec2>& out) const {
  out.clear();
  for (uint32_t slot : slots) {
    const Node& n = nodes_[slot];
    for (const Vec2& p : n.points) {
      const Vec2 q = n.estimate.transform(p);
      if (std::abs(q.x - centre.x) <= half_extent && std::abs(q.y - centre.y) <= half_extent)
        out.push_back(q);
    }
  }
}

namespace {

// Copies the cells of `grid` within `half_extent` of `centre` (whole cells, the grid's own
// alignment, so a match against the copy is the match against the grid).
GridGeometry copy_window(const GridView& grid, Vec2 centre, double half_extent, std::vector<uint8_t>& cells) {
  const GridGeometry& g = grid.geometry;
  GridGeometry window;
  window.resolution = g.resolution;
  if (g.cells() == 0 || grid.classes.size() < g.cells()) {  // an empty view stays empty
    cells.clear();
    return window;
  }
  const Cell lo = g.clamped_cell_at({centre.x - half_extent, centre.y - half_extent});
  const Cell hi = g.clamped_cell_at({centre.x + half_extent, centre.y + half_extent});
  window.origin = g.corner(lo);
  window.width = hi.x - lo.x + 1;
  window.height = hi.y - lo.y + 1;
  cells.resize(window.cells());
  for (int32_t row = 0; row < window.height; ++row) {
    const size_t from = g.index({lo.x, lo.y + row});
    std::copy_n(grid.classes.begin() + static_cast<std::ptrdiff_t>(from), window.width,
                cells.begin() + static_cast<std::ptrdiff_t>(window.index({0, row})));
  }
  return window;
}

}  // namespace

void PoseCorrector::prepare(Keyframe&& keyframe, const GridView& grid, bool match, MatchJob& job) {
  Robot& rb = robots_[keyframe.robot];
  job.generation = rb.generation;
  job.prepared_correction = rb.state.map_from_odom;
  job.predicted = rb.state.map_from_odom.compose(keyframe.odom);

  job.previous.reset();
  if (rb.last_node && nodes_[*rb.last_node].segment == keyframe.segment) job.previous = rb.last_node;
  job.odom_motion = job.odom_relative = Pose{};
  job.odom_cov = diagonal(kSegmentSigma_m, kSegmentSigma_m, kSegmentSigma_rad);
  job.standing = false;
  if (job.previous) {
    const Pose& previous_odom = nodes_[*job.previous].odom;
    job.odom_motion = previous_odom.inverse().compose(keyframe.odom);
    const Pose driven =
        options_.odometry_direction ? rb.odometry_direction.applied(job.odom_motion) : job.odom_motion;
    job.odom_relative = options_.odometry_calibration ? rb.odometry_calibration.corrected(driven) : driven;
    job.predicted = rb.state.map_from_odom.compose(previous_odom).compose(job.odom_relative);
    const Pose since_moving =
        rb.last_moving_odom ? rb.last_moving_odom->inverse().compose(keyframe.odom) : job.odom_motion;
    job.standing = keyframe.travel_m < options_.standing_travel_m &&
                   keyframe.turn_rad < options_.standing_turn_rad &&
                   norm(since_moving.position()) < options_.standing_travel_m &&
                   std::abs(since_moving.theta) < options_.standing_turn_rad;
    job.odom_cov = rb.odometry_trust.scaled(odometry_covariance(job.odom_relative));
    const double d = norm(job.odom_relative.position());
    grow_by_motion(rb.chain_cov, job.odom_cov, d);
    grow_by_motion(rb.pose_cov, job.odom_cov, d);
  } else {
    rb.chain_cov = job.odom_cov;
    rb.pose_cov = rb.last_node ? job.odom_cov : diagonal(kStartSigma_m, kStartSigma_m, kStartSigma_rad);
  }
  if (!job.standing) rb.last_moving_odom = keyframe.odom;
  if (job.previous) {
    job.heading_variance = rb.heading_variance;  // the matching adds the motion's
  } else {
    const double sigma = rb.last_node ? kSegmentSigma_rad : kStartSigma_rad;
    job.heading_variance = sigma * sigma;
    rb.anchors_walls = rb.last_node ? 0 : kAnchoringKeyframes;  // a start, not a jump
  }

  job.map_axis = options_.wall_heading ? wall_axes_.axis() : std::nullopt;
  if (job.standing) match = false;
  job.track = match;
  job.tie = false;
  job.relocalise = false;
  job.wide_needed = job.wide_permitted = false;
  if (match) {
    // The window the tracking match can read: the farthest point, the search window and the
    // likelihood field's blur around it.
    double reach = 0.0;
    for (const Vec2& p : keyframe.points) reach = std::max(reach, norm(p));
    const double track_reach =
        keyframe.scans ? std::max(options_.scan_track_window.linear_m, options_.scan_recovery_window.linear_m)
                       : options_.track_window.linear_m;
    const double half = reach + track_reach + options_.window_margin_m;
    job.track_geometry = copy_window(grid, job.predicted.position(), half, job.track_cells);
    job.track_points.clear();
    // What the keyframe can see, up to local_reach_m: a 4 m sensor's local map stays as small as it was.
    const double local_reach = std::min(options_.local_reach_m, reach + kLocalReachMargin_m);
    if (options_.point_refine) window_points(job.predicted.position(), local_reach, half, job.track_points);

    // The tie to the old map, planned here where the pose graph lives (around the prediction: the
    // narrow match moves the keyframe by at most the tracking window, which the grid covers).
    old_neighbours(keyframe.robot, keyframe.first_stamp_ns, job.predicted.position(),
                   options_.closure_radius_m, neighbours_);
    if (!rb.operator_pose && static_cast<int>(neighbours_.size()) >= options_.closure_min_keyframes) {
      if (schedule_.allow_tie(rb.schedule)) {
        const double chain_sigma = std::sqrt(std::max(rb.chain_cov(0, 0), rb.chain_cov(1, 1)));
        job.wide_needed = chain_sigma > options_.tied_sigma_m;
        // Normal load: a wide search whenever tracking fails too; loaded: only the ones the
        // schedule grants, taken only when certainly needed.
        job.wide_permitted = schedule_.load() == Load::Normal ||
                             (job.wide_needed && schedule_.allow_wide(rb.schedule, keyframe.first_stamp_ns));
        if (job.wide_needed && !job.wide_permitted) {
          ++stats_.wide_skipped;
        } else {
          job.tie = true;
          job.anchor = neighbours_.front();
          job.neighbours = neighbours_.size();
          const double window =
              job.wide_permitted ? options_.closure_window.linear_m : options_.track_window.linear_m;
          const double tie_half = local_reach + window + options_.track_window.linear_m;
          job.tie_geometry = draw_local_grid(neighbours_, job.predicted.position(), tie_half,
                                             grid.geometry.resolution, job.tie_cells);
          job.tie_points.clear();
          if (options_.point_refine)
            gather_points(neighbours_, job.predicted.position(), tie_half, job.tie_points);
        }
      } else {
        ++stats_.ties_skipped;
      }
    }
    // The pose's own uncertainty in the map, not the chain's since its last tie: a robot just switched
    // on at a trusted start has an untied chain but a known pose.
    const double pose_sigma = std::sqrt(std::max(rb.pose_cov(0, 0), rb.pose_cov(1, 1)));
    if (options_.relocalise && !options_.localise_only && !keyframe.scans && !rb.operator_pose &&
        pose_sigma > options_.relocalise_sigma_m && schedule_.load() == Load::Normal)
      prepare_relocalisation(rb, keyframe, job);
  }
  job.keyframe = std::move(keyframe);
}

void PoseCorrector::recover_track(ScanMatcher& matcher, const GridView& view, MatchJob& job,
                                  Result<MatchResult>& narrow) const {
  const SearchWindow& wide = options_.scan_recovery_window;
  // Only what the search reads: its points reach max_point_range_m, not the scan's farthest return.
  const double half =
      job.recovery_search.options().max_point_range_m + wide.linear_m + options_.window_margin_m;
  const GridGeometry around = copy_window(view, job.predicted.position(), half, job.recovery_cells);
  if (!job.recovery_search.set_map(GridView{around, job.recovery_cells})) return;
  const auto found =
      job.recovery_search.search(job.keyframe.points, {job.predicted, wide.linear_m, wide.angular_rad});
  if (!found) return;
  auto again = matcher.match(view, job.keyframe.points, found->pose, options_.scan_track_window,
                             options_.scan_independent_points);
  if (again && !again->at_window_edge &&
      (!narrow || again->score > narrow->score + options_.scan_recovery_gain))
    narrow = std::move(again);
}

void PoseCorrector::match_keyframe(ScanMatcher& matcher, MatchJob& job) const {
  job.narrow.reset();
  job.point_refined = false;
  job.tie_match.reset();
  job.wide = job.wide_skipped = false;
  job.wall_reading.reset();
  job.wall_heading.reset();
  job.relocalised.reset();
  job.estimate = job.predicted;
  job.cov = Eigen::Matrix3d::Zero();
  if (!job.track) {
    job.tracked = job.estimate;
    if (job.previous) job.heading_variance += job.odom_cov(2, 2);
    return;
  }
  // 1. Track: the keyframe against the grid, near the prediction.
  const auto& points = job.keyframe.points;
  const bool scans = job.keyframe.scans;
  const double independent = scans ? options_.scan_independent_points : 0.0;
  const SearchWindow& track_window = scans ? options_.scan_track_window : options_.track_window;
  const GridView track_view{job.track_geometry, job.track_cells};
  auto narrow = matcher.match(track_view, points, job.predicted, track_window, independent);
  if (scans && (!narrow || narrow->at_window_edge)) recover_track(matcher, track_view, job, narrow);
  if (narrow) {
    // Fused with the odometry prediction by their covariances (a Kalman update): a sparse
    // keyframe's match is noisier than half a metre of odometry, and taking it as is would
    // random-walk the pose where the map is only the robot's own recent trail.
    const double scale = scans ? options_.scan_track_variance_scale : options_.track_variance_scale;
    job.cov = with_floor(narrow->covariance * scale, 0.005, 0.002);
    // The search read the grid's cells; the points of the keyframes around place the walls within them.
    if (options_.point_refine) {
      job.refiner.set_reference(job.track_points);
      if (const auto refined = job.refiner.refine(points, narrow->pose, job.cov)) {
        narrow->pose = refined->pose;
        job.point_refined = true;
      }
    }
    job.estimate = fuse(job.predicted, job.odom_cov, narrow->pose, job.cov);
    job.narrow = *narrow;
  }
  job.tracked = job.estimate;
  // The heading's variance grows by the motion's, as tracking measured it.
  if (job.previous) {
    job.heading_variance += job.narrow ? fused_covariance(job.odom_cov, job.cov)(2, 2) : job.odom_cov(2, 2);
  }
  // 2. The walls' heading: a Kalman update of the heading alone, about the keyframe's origin.
  if (options_.wall_heading) job.wall_reading = job.wall_reader.read(points, options_.wall_axis);
  if (job.wall_reading) {
    // The keyframe's points were gathered over its own motion, along which its odometry heading
    // drifted: a robot known to drift reads its walls a little bent.
    job.wall_variance = job.wall_reading->sigma * job.wall_reading->sigma +
                        options_.wall_heading_floor_rad * options_.wall_heading_floor_rad +
                        (job.previous ? job.odom_cov(2, 2) : 0.0);
  }
  if (job.wall_reading && job.map_axis) {
    const double correction = heading_correction(*job.map_axis, *job.wall_reading, job.estimate.theta);
    if (std::abs(correction) <= options_.wall_heading_gate_rad) {
      const double gain = job.heading_variance / (job.heading_variance + job.wall_variance);
      job.wall_heading = job.estimate.theta + correction;
      job.heading_variance *= 1.0 - gain;
      job.estimate.theta = wrap_angle(job.estimate.theta + gain * correction);
    }
  }
  if (job.relocalise) search_relocalisation(matcher, job);
  if (!job.tie) return;
  // 3. Tie to the old map: against old keyframes only; a wide search (a loop closure) when the
  // robot has not been tied for a while or tracking failed.
  const bool wide = !job.narrow || job.wide_needed;
  if (wide && !job.wide_permitted) {
    job.wide_skipped = true;
    return;
  }
  job.wide = wide;
  if (auto tie = matcher.match(GridView{job.tie_geometry, job.tie_cells}, points, job.estimate,
                               wide ? options_.closure_window : track_window, independent)) {
    if (options_.point_refine) {
      job.refiner.set_reference(job.tie_points);
      if (const auto refined = job.refiner.refine(points, tie->pose, tie->covariance))
        tie->pose = refined->pose;
    }
    job.tie_match = *tie;
  }
}

}  // namespace slam::correction
