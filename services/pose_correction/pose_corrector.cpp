#include "pose_correction/pose_corrector.hpp"

#include <spdlog/spdlog.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <utility>

#include "pose_correction/graph_optimizer.hpp"

namespace slam::correction {

namespace {

bool finite(const Pose& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

Eigen::Matrix3d diagonal(double sx, double sy, double st) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  m(0, 0) = sx * sx;
  m(1, 1) = sy * sy;
  m(2, 2) = st * st;
  return m;
}

// A symmetric positive-definite covariance with a floor, so an over-confident match cannot make
// the graph stiff and a degenerate one cannot make it singular.
Eigen::Matrix3d with_floor(const Eigen::Matrix3d& c, double sigma_m, double sigma_rad) {
  Eigen::Matrix3d out = 0.5 * (c + c.transpose());
  out += diagonal(sigma_m, sigma_m, sigma_rad);
  return out;
}

// The information-weighted mean of two estimates of one pose (angles compared wrapped).
Pose fuse(const Pose& a, const Eigen::Matrix3d& ca, const Pose& b, const Eigen::Matrix3d& cb) {
  const Eigen::Matrix3d gain = ca * (ca + cb).inverse();
  const Eigen::Vector3d delta(b.x - a.x, b.y - a.y, wrap_angle(b.theta - a.theta));
  const Eigen::Vector3d step = gain * delta;
  return {a.x + step.x(), a.y + step.y(), wrap_angle(a.theta + step.z())};
}

// The tracking update: like fuse(), but a match that agrees with the odometry prediction within
// kTrackDeadBandSigmas of their combined uncertainty moves nothing, and a farther one only by the
// part beyond it. A sparse keyframe's match carries a little noise of its own; taken at face value
// every keyframe, it random-walks a robot whose odometry is right (drift 0 became worse than none).
Pose track_update(const Pose& predicted, const Eigen::Matrix3d& odom_cov, const Pose& matched,
                  const Eigen::Matrix3d& match_cov) {
  constexpr double kTrackDeadBandSigmas = 0.5;
  const Eigen::Vector3d delta(matched.x - predicted.x, matched.y - predicted.y,
                              wrap_angle(matched.theta - predicted.theta));
  const double mahalanobis = std::sqrt(delta.dot((odom_cov + match_cov).inverse() * delta));
  if (!(mahalanobis > kTrackDeadBandSigmas)) return predicted;
  const Eigen::Vector3d beyond = delta * (1.0 - kTrackDeadBandSigmas / mahalanobis);
  const Pose shrunk{predicted.x + beyond.x(), predicted.y + beyond.y(),
                    wrap_angle(predicted.theta + beyond.z())};
  return fuse(predicted, odom_cov, shrunk, match_cov);
}

Eigen::Matrix3d fused_covariance(const Eigen::Matrix3d& ca, const Eigen::Matrix3d& cb) {
  return (ca.inverse() + cb.inverse()).inverse();
}

constexpr size_t kMaxNeighbours = 40;
constexpr double kPointReach_m = 4.5;   // sensor range plus margin: local grids cover it
constexpr double kTiedSigma_m = 0.05;   // chain uncertainty above which a wide search is needed
constexpr double kStartSigma_m = 0.05;  // a robot's first keyframe: its start pose is trusted
constexpr double kStartSigma_rad = 0.02;
constexpr double kSegmentSigma_m = 2.0;  // after an odometry jump the pose is barely known
constexpr double kSegmentSigma_rad = 0.5;
constexpr double kOperatorSigma_m = 0.02;
constexpr double kOperatorSigma_rad = 0.01;

}  // namespace

PoseCorrector::PoseCorrector(const CorrectorOptions& options)
    : options_(options), matcher_(options.matcher), optimizer_(std::make_unique<GraphOptimizer>()) {}

PoseCorrector::~PoseCorrector() = default;

uint32_t PoseCorrector::robot_index(std::string_view robot) {
  const std::string key(robot);
  if (auto it = robot_ids_.find(key); it != robot_ids_.end()) return it->second;
  const auto index = static_cast<uint32_t>(robots_.size());
  Robot robot_state{key,          KeyframeBuilder(options_.keyframe),
                    {},           Eigen::Matrix3d::Zero(),
                    std::nullopt, std::nullopt,
                    std::nullopt, false,
                    false};
  robot_state.state.robot = key;
  robots_.push_back(std::move(robot_state));
  robot_ids_.emplace(key, index);
  return index;
}

Result<uint64_t> PoseCorrector::add(std::string_view robot, int64_t stamp_ns, const Pose& odom_pose,
                                    bool has_heading, std::span<const Vec2> hits) {
  const bool points_finite =
      std::all_of(hits.begin(), hits.end(), [](Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); });
  if (!finite(odom_pose) || !points_finite) {
    ++stats_.rejected_inputs;
    return Error{"observation has a non-finite pose or point"};
  }
  const uint32_t r = robot_index(robot);
  Robot& rb = robots_[r];
  rb.has_heading = has_heading;
  auto step = rb.builder.add(next_id_, r, stamp_ns, odom_pose, has_heading, hits);
  if (step == KeyframeBuilder::Step::Jump) {
    if (rb.builder.open()) closed_.push_back(rb.builder.take());
    ++stats_.segments;
    step = rb.builder.add(next_id_, r, stamp_ns, odom_pose, has_heading, hits);
  }
  const uint64_t id = rb.builder.open_id();
  if (id == next_id_) ++next_id_;
  if (step == KeyframeBuilder::Step::AddedAndClosed) closed_.push_back(rb.builder.take());
  return id;
}

void PoseCorrector::process(const GridView& grid, int64_t now_ns, std::vector<KeyframeCorrection>& out) {
  for (Robot& rb : robots_) {
    if (rb.builder.stale(now_ns)) closed_.push_back(rb.builder.take());
  }
  for (Keyframe& keyframe : closed_) finalise(std::move(keyframe), grid, out);
  closed_.clear();
  if (closure_since_optimise_ || tied_since_optimise_ >= options_.optimise_every) start_optimisation();
}

Eigen::Matrix3d PoseCorrector::odometry_covariance(const Pose& relative) const {
  const double d = norm(relative.position());
  const double st = options_.odom_sigma_m_per_sqrt_m * std::sqrt(d) + 0.002;
  const double sr = options_.odom_sigma_rad_per_m * d + 0.01 * std::sqrt(std::abs(relative.theta)) + 0.002;
  return diagonal(st, st, sr);
}

void PoseCorrector::old_neighbours(uint32_t robot, int64_t stamp_ns, Vec2 centre,
                                   std::vector<uint32_t>& out) {
  out.clear();
  index_.near(centre, options_.closure_radius_m, out);
  const auto min_age_ns = static_cast<int64_t>(options_.old_age_s * 1e9);
  std::erase_if(out, [&](uint32_t slot) {
    const Node& n = nodes_[slot];
    const bool old = n.robot != robot || stamp_ns - n.stamp_ns >= min_age_ns;
    return !old || n.points.empty() || distance(n.estimate.position(), centre) > options_.closure_radius_m;
  });
  std::sort(out.begin(), out.end(), [&](uint32_t a, uint32_t b) {
    return distance(nodes_[a].estimate.position(), centre) < distance(nodes_[b].estimate.position(), centre);
  });
  if (out.size() > kMaxNeighbours) out.resize(kMaxNeighbours);
}

GridView PoseCorrector::draw_local_grid(std::span<const uint32_t> slots, Vec2 centre, double half_extent,
                                        double resolution) {
  GridGeometry g;
  g.resolution = resolution;
  g.width = g.height = static_cast<int32_t>(std::ceil(2.0 * half_extent / resolution));
  g.origin = {centre.x - half_extent, centre.y - half_extent};
  local_cells_.assign(g.cells(), 0);
  for (uint32_t slot : slots) {
    const Node& n = nodes_[slot];
    for (const Vec2& p : n.points) {
      if (const auto c = g.cell_at(n.estimate.transform(p))) local_cells_[g.index(*c)] = 2;  // occupied
    }
  }
  return GridView{g, local_cells_};
}

void PoseCorrector::add_edge(EdgeKind kind, uint32_t from, uint32_t to, const Pose& measurement,
                             const Eigen::Matrix3d& cov) {
  GraphEdge e;
  e.kind = kind;
  e.from = nodes_[from].id;
  e.to = nodes_[to].id;
  e.measurement = measurement;
  e.information = cov.inverse();
  edges_.push_back(e);
}

void PoseCorrector::finalise(Keyframe&& keyframe, const GridView& grid,
                             std::vector<KeyframeCorrection>& out) {
  Robot& rb = robots_[keyframe.robot];
  ++stats_.keyframes;
  const Pose predicted = rb.state.map_from_odom.compose(keyframe.odom);

  std::optional<uint32_t> previous;
  if (rb.last_node && nodes_[*rb.last_node].segment == keyframe.segment) previous = rb.last_node;
  Pose odom_relative;
  Eigen::Matrix3d odom_cov = diagonal(kSegmentSigma_m, kSegmentSigma_m, kSegmentSigma_rad);
  if (previous) {
    odom_relative = nodes_[*previous].odom.inverse().compose(keyframe.odom);
    odom_cov = odometry_covariance(odom_relative);
    const double d = norm(odom_relative.position());
    rb.chain_cov += odom_cov;
    rb.chain_cov(0, 0) += rb.chain_cov(2, 2) * d * d;  // heading uncertainty swings the position
    rb.chain_cov(1, 1) += rb.chain_cov(2, 2) * d * d;
  } else {
    rb.chain_cov = odom_cov;
  }

  // 1. Track: the keyframe against the whole grid, near the prediction.
  Pose estimate = predicted;
  Eigen::Matrix3d cov = rb.chain_cov;
  CorrectionSource source = rb.state.source;
  const auto narrow = matcher_.match(grid, keyframe.points, predicted, options_.track_window);
  if (narrow) {
    // Fused with the odometry prediction by their covariances (a Kalman update): a sparse
    // keyframe's match is noisier than half a metre of odometry, and taking it as is would
    // random-walk the pose where the map is only the robot's own recent trail.
    cov = with_floor(narrow->covariance, 0.005, 0.002);
    estimate = track_update(predicted, odom_cov, narrow->pose, cov);
    source = CorrectionSource::Match;
    ++stats_.matched;
  } else {
    ++stats_.unmatched;
  }
  const bool tracked = narrow.is_ok();

  // 2. Tie to the old map: against old keyframes only; a wide search (a loop closure) when the
  // robot has not been tied for a while or tracking failed.
  std::optional<uint32_t> anchor;
  Pose anchored_estimate;
  Eigen::Matrix3d anchored_cov;
  bool closure = false;
  const bool operator_set = rb.operator_pose.has_value();
  old_neighbours(keyframe.robot, keyframe.first_stamp_ns, estimate.position(), neighbours_);
  if (!operator_set && static_cast<int>(neighbours_.size()) >= options_.closure_min_keyframes) {
    const double chain_sigma = std::sqrt(std::max(rb.chain_cov(0, 0), rb.chain_cov(1, 1)));
    const bool wide = !tracked || chain_sigma > kTiedSigma_m;
    const SearchWindow window = wide ? options_.closure_window : options_.track_window;
    const GridView local = draw_local_grid(neighbours_, estimate.position(), kPointReach_m + window.linear_m,
                                           grid.geometry.resolution);
    if (wide) ++stats_.closures_tried;
    const auto tie = matcher_.match(local, keyframe.points, estimate, window);
    if (tie && tie->score >= options_.closure_min_score) {
      const Eigen::Matrix3d tie_cov = with_floor(tie->covariance, 0.02, 0.01);
      const ConsistencyCheck check;
      // A closure must be unambiguous and agree with the uncertainty accumulated since the last tie.
      if (!wide ||
          (DistinctMatch{}.accepts(*tie) && check.accepts(estimate, tie->pose, rb.chain_cov + tie_cov))) {
        anchor = neighbours_.front();
        anchored_estimate = tie->pose;
        anchored_cov = tie_cov;
        if (wide) {
          closure = distance(tie->pose.position(), estimate.position()) > 0.02 ||
                    std::abs(wrap_angle(tie->pose.theta - estimate.theta)) > 0.005;
          ++stats_.closures_accepted;
          spdlog::info(
              "loop closure: robot {} keyframe {} moved {:.3f} m, {:.2f} deg against {} old keyframes",
              rb.name, keyframe.id, distance(tie->pose.position(), estimate.position()),
              wrap_angle(tie->pose.theta - estimate.theta) * 57.29578, neighbours_.size());
        }
      } else {
        ++stats_.closures_rejected;
      }
    }
  }
  if (anchor) {
    if (closure) {
      bend_chain(keyframe.robot, keyframe.segment, estimate, anchored_estimate);
      source = CorrectionSource::Loop;
      ++rb.state.loop_closures;
      closure_since_optimise_ = true;
      estimate = anchored_estimate;
      rb.chain_cov = anchored_cov;
    } else {
      // A tie inside the tracking window: the same update, weighted by what the robot has
      // accumulated since it was last tied.
      estimate = fuse(estimate, rb.chain_cov, anchored_estimate, anchored_cov);
      rb.chain_cov = fused_covariance(rb.chain_cov, anchored_cov);
    }
    cov = anchored_cov;
    ++tied_since_optimise_;
  }
  if (operator_set) {
    estimate = rb.operator_pose->compose(keyframe.odom);
    if (tracked) estimate = narrow->pose;
    source = CorrectionSource::Operator;
    rb.chain_cov = diagonal(kOperatorSigma_m, kOperatorSigma_m, kOperatorSigma_rad);
  }

  // 3. The node and its edges.
  const auto slot = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back(Node{keyframe.id, keyframe.robot, keyframe.segment, keyframe.first_stamp_ns, keyframe.odom,
                        estimate, std::move(keyframe.points), false});
  index_.insert(slot, estimate.position());
  if (previous) {
    // Tracking refines the odometry between consecutive keyframes; a tie or closure jump is not a
    // motion, so then the odometry itself is the edge.
    if (tracked && !anchor) {
      add_edge(EdgeKind::Sequential, *previous, slot, nodes_[*previous].estimate.inverse().compose(estimate),
               with_floor(cov, 0.01, 0.005));
    } else {
      add_edge(EdgeKind::Sequential, *previous, slot, odom_relative, odom_cov);
    }
  }
  if (anchor) {
    add_edge(EdgeKind::LoopClosure, *anchor, slot, nodes_[*anchor].estimate.inverse().compose(estimate), cov);
  }
  if (operator_set || !previous) {
    GraphEdge prior;
    prior.kind = EdgeKind::Prior;
    prior.from = prior.to = keyframe.id;
    prior.measurement = estimate;
    const bool first = !rb.last_node;
    prior.information = (operator_set ? diagonal(kOperatorSigma_m, kOperatorSigma_m, kOperatorSigma_rad)
                         : first      ? diagonal(kStartSigma_m, kStartSigma_m, kStartSigma_rad)
                                      : diagonal(kSegmentSigma_m, kSegmentSigma_m, kSegmentSigma_rad))
                            .inverse();
    edges_.push_back(prior);
  }
  rb.operator_pose.reset();
  rb.last_node = slot;
  if (anchor || operator_set || !previous) rb.last_tied = slot;

  const Pose before = rb.state.map_from_odom.compose(keyframe.odom);
  rb.state.map_from_odom = estimate.compose(keyframe.odom.inverse());
  if (distance(before.position(), estimate.position()) > kJumpWarning_m) {
    spdlog::warn("pose correction: robot {} moved {:.2f} m by keyframe {} (tracked {}, tied {}, closure {})",
                 rb.name, distance(before.position(), estimate.position()), keyframe.id, tracked,
                 anchor.has_value(), closure);
  }
  rb.state.covariance = cov;
  rb.state.segment = keyframe.segment;
  ++rb.state.keyframes;
  mark_changed(rb, source);
  out.push_back(
      KeyframeCorrection{keyframe.id, rb.name, keyframe.segment, keyframe.odom, rb.state.map_from_odom});
}

void PoseCorrector::mark_changed(Robot& robot, CorrectionSource source) {
  robot.state.source = source;
  ++robot.state.version;
  robot.changed = true;
}

Status PoseCorrector::set_initial_pose(std::string_view robot, const Pose& map_pose) {
  if (!finite(map_pose)) {
    ++stats_.rejected_inputs;
    return Error{"initial pose is not finite"};
  }
  if (!knows(robot)) {
    ++stats_.rejected_inputs;
    return Error{"unknown robot '" + std::string(robot) + "': no observation from it yet"};
  }
  Robot& rb = robots_[robot_ids_.at(std::string(robot))];
  const Pose odom = rb.builder.last_odom();
  Pose correction;
  if (rb.has_heading) {
    correction = map_pose.compose(odom.inverse());
  } else {
    // Only the odometry frame's rotation is given: place the last reported position at the pose.
    const Pose rotation{0.0, 0.0, map_pose.theta};
    const Vec2 rotated = rotation.transform(odom.position());
    correction = Pose{map_pose.x - rotated.x, map_pose.y - rotated.y, wrap_angle(map_pose.theta)};
  }
  rb.operator_pose = correction;
  rb.state.map_from_odom = correction;
  ++epoch_;
  rb.chain_cov = diagonal(kOperatorSigma_m, kOperatorSigma_m, kOperatorSigma_rad);
  rb.state.covariance = rb.chain_cov;
  mark_changed(rb, CorrectionSource::Operator);
  return Status::ok();
}

void PoseCorrector::restore(std::span<const KeyframeCorrection> keyframes) {
  for (const KeyframeCorrection& k : keyframes) {
    const uint32_t r = robot_index(k.robot);
    Robot& rb = robots_[r];
    nodes_.push_back(Node{k.id, r, k.segment, 0, k.odom, k.correction.compose(k.odom), {}, true});
    rb.state.map_from_odom = k.correction;
    rb.state.segment = k.segment;
    ++rb.state.keyframes;
    next_id_ = std::max(next_id_, k.id + 1);
  }
  for (Robot& rb : robots_) {
    if (rb.state.keyframes > 0) mark_changed(rb, CorrectionSource::Restored);
  }
  rebuild_index();
}

bool PoseCorrector::knows(std::string_view robot) const {
  const auto it = robot_ids_.find(std::string(robot));
  return it != robot_ids_.end() && robots_[it->second].builder.has_last();
}

Pose PoseCorrector::correction(std::string_view robot) const {
  const auto it = robot_ids_.find(std::string(robot));
  return it == robot_ids_.end() ? Pose{} : robots_[it->second].state.map_from_odom;
}

void PoseCorrector::take_changed(std::vector<RobotCorrection>& out) {
  for (Robot& rb : robots_) {
    if (!rb.changed) continue;
    rb.changed = false;
    out.push_back(rb.state);
  }
}

}  // namespace slam::correction
