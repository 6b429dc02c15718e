// The requests about one robot: an operator's initial pose, keyframes restored after a restart, an
// operator's reset, and what the mapper asks of each robot's correction (PoseCorrector).
#include <string>
#include <unordered_set>

#include "pose_correction/gaussian_pose.hpp"
#include "pose_correction/pose_corrector.hpp"

namespace slam::correction {

void PoseCorrector::mark_changed(Robot& robot, CorrectionSource source) {
  robot.state.source = source;
  ++robot.state.version;
  robot.changed = true;
}

Status PoseCorrector::set_initial_pose(std::string_view robot, const Pose& map_pose) {
  if (!is_finite(map_pose)) {
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
  if (rb.state.placement != Placement::Placed) place(rb, correction, 1.0);  // the operator knows
  rb.rejected.clear();
  rb.operator_pose = correction;
  rb.state.map_from_odom = correction;
  ++epoch_;
  rb.chain_cov = diagonal(kOperatorSigma_m, kOperatorSigma_m, kOperatorSigma_rad);
  rb.pose_cov = rb.chain_cov;
  rb.heading_variance = kOperatorSigma_rad * kOperatorSigma_rad;
  rb.anchors_walls = kAnchoringKeyframes;
  rb.state.covariance = rb.pose_cov;
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
    if (rb.state.keyframes == 0) continue;
    // Its keyframes were stored once it was placed: where it is was known, and it still is.
    rb.state.placement = Placement::Placed;
    rb.state.localisation_score = 1.0;
    mark_changed(rb, CorrectionSource::Restored);
  }
  rebuild_index();
}

size_t PoseCorrector::reset_robot(std::string_view robot) {
  const auto it = robot_ids_.find(std::string(robot));
  if (it == robot_ids_.end()) return 0;
  const uint32_t r = it->second;
  Robot& rb = robots_[r];
  std::unordered_set<uint64_t> ids;
  for (Node& n : nodes_) {
    if (n.robot != r || n.removed) continue;
    ids.insert(n.id);
    n.removed = true;
    n.points = {};  // also keeps it out of every local grid
    ++removed_nodes_;
  }
  std::erase_if(edges_, [&](const GraphEdge& e) { return ids.contains(e.from) || ids.contains(e.to); });
  std::erase_if(closed_, [&](const Keyframe& k) { return k.robot == r; });
  rb.held.clear();
  rb.rejected.clear();
  rb.hypothesis.reset();
  rb.confirmations = 0;
  rb.searched_at.reset();
  rb.searches_unfound = 0;
  std::erase_if(pending_moved_, [&](const KeyframeCorrection& k) { return ids.contains(k.id); });
  if (rb.builder.open()) (void)rb.builder.take();
  rb.builder.start_segment();
  ++rb.generation;  // its keyframe on the worker, if any, is dropped when it lands
  rb.last_node.reset();
  rb.recent_nodes.clear();
  rb.relocalise_hypothesis.reset();
  rb.relocalise_agreed = 0;
  rb.last_tied.reset();
  rb.operator_pose.reset();
  rb.last_moving_odom.reset();
  rb.unmatched_in_row = 0;  // its tracking is watched afresh (watch_tracking)
  rb.track_scores.clear();
  rb.track_score_next = 0;
  rb.chain_cov = Eigen::Matrix3d::Zero();
  rb.pose_cov = Eigen::Matrix3d::Zero();
  rb.heading_variance = 0.0;
  rb.schedule = {};
  rb.state.keyframes = 0;
  rb.state.loop_closures = 0;
  ++epoch_;  // a running optimisation still holds its keyframes: its result is stale
  rebuild_index();
  ++stats_.robots_reset;
  return ids.size();
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
