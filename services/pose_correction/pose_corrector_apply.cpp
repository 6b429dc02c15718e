// What a finished match does to the graph and to its robot's correction (PoseCorrector::apply): the
// match is carried into the robot's current correction, the tracking counted and learnt from, a tie
// or loop closure decided and applied, the keyframe added as a node with its edges, and the robot's
// published state moved to it.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "pose_correction/gaussian_pose.hpp"
#include "pose_correction/pose_corrector.hpp"

namespace slam::correction {

namespace {

// A closure match's figures for the log: what each gate saw.
std::string describe(const MatchResult& m, size_t points, const Eigen::Matrix3d& chain_cov) {
  return fmt::format(
      "{} points, score {:.2f}, sigma {:.3f} / {:.3f} m, {:.2f} deg, flat {}, ambiguity {:.2f}, "
      "window edge {}, chain sigma {:.3f} m",
      points, m.score, std::sqrt(m.covariance(0, 0)), std::sqrt(m.covariance(1, 1)),
      to_degrees(std::sqrt(m.covariance(2, 2))), m.flat_directions, m.ambiguity, m.at_window_edge,
      std::sqrt(std::max(chain_cov(0, 0), chain_cov(1, 1))));
}

}  // namespace

void PoseCorrector::apply(MatchJob& job, std::vector<KeyframeCorrection>& out) {
  Robot& rb = robots_[job.keyframe.robot];
  ++stats_.keyframes;
  carry_into_correction(job, rb.state.map_from_odom);
  rb.heading_variance = job.heading_variance;
  // The motion from the previous keyframe as tracking measured it, before the walls' heading, a tie
  // or a closure moves this keyframe (a closure also bends the previous one): each of those is its
  // own edge.
  const Pose tracked_motion =
      job.previous ? nodes_[*job.previous].estimate.inverse().compose(job.tracked) : Pose{};
  CorrectionSource source = learn_from_tracking(job, rb);
  if (options_.localise_only && job.narrow) {
    // A match against the fixed map holds the robot to it as a tie to old keyframes would.
    const Eigen::Matrix3d cov = with_floor(job.narrow->covariance, 0.02, 0.01);
    rb.chain_cov = fused_covariance(rb.chain_cov, cov);
    rb.pose_cov = fused_covariance(rb.pose_cov, cov);
  }
  const bool operator_set = rb.operator_pose.has_value();
  TieDecision tie = decide_tie(job, rb, operator_set);
  if (!operator_set && !tie.closure) confirm_relocalisation(job, rb, tie);
  Pose estimate = job.estimate;
  if (tie.anchor) {
    estimate = apply_tie(job.keyframe, rb, tie, estimate);
    if (tie.closure) source = CorrectionSource::Loop;
  }
  if (operator_set) {
    estimate = apply_operator_pose(job, rb);
    source = CorrectionSource::Operator;
  }
  const uint32_t slot = add_node_and_edges(job, rb, estimate, tracked_motion, tie, operator_set);
  learn_wall_axes(job, rb, estimate);
  rb.operator_pose.reset();
  rb.last_node = slot;
  if (!options_.localise_only) {  // its trail is searched among old keyframes, which it has none of
    if (rb.recent_nodes.size() == kRecentNodes) rb.recent_nodes.erase(rb.recent_nodes.begin());
    rb.recent_nodes.push_back(slot);
  }
  if (tie.anchor || operator_set || !job.previous) rb.last_tied = slot;
  if (keyframe_observer_) {
    const Node& node = nodes_[slot];
    const bool tracked = job.narrow.has_value();
    keyframe_observer_(KeyframeDecision{rb.name, node.stamp_ns, node.odom, job.predicted,
                                        tracked ? std::optional<Pose>(job.narrow->pose) : std::nullopt,
                                        tracked ? job.narrow->covariance : Eigen::Matrix3d::Zero(),
                                        operator_set ? std::nullopt : job.wall_heading, estimate,
                                        tie.anchor.has_value(), tie.closure, rb.chain_cov});
  }
  publish_keyframe(job, rb, estimate, source, tie, out);
  watch_tracking(job, rb);
}

void PoseCorrector::carry_into_correction(MatchJob& job, const Pose& correction) const {
  // An optimisation that landed while the keyframe was matched moved the robot's correction: move
  // what was matched with it.
  const Pose moved = correction.compose(job.prepared_correction.inverse());
  auto carry = [&](Pose& p) { p = moved.compose(p); };
  carry(job.predicted);
  carry(job.tracked);
  carry(job.estimate);
  if (job.wall_heading) *job.wall_heading = wrap_angle(*job.wall_heading + moved.theta);
  if (job.narrow) carry(job.narrow->pose);
  if (job.tie_match) carry(job.tie_match->pose);
  if (job.relocalised) carry(job.relocalised->pose);
}

CorrectionSource PoseCorrector::learn_from_tracking(const MatchJob& job, Robot& rb) {
  const auto& narrow = job.narrow;
  if (!narrow) {
    if (!job.standing) ++stats_.unmatched;
    return rb.state.source;
  }
  ++stats_.matched;
  if (job.point_refined) ++stats_.point_refined;
  // How far the match moved the odometry prediction teaches how far this robot's odometry holds.
  if (job.previous && narrow->flat_directions == 0) {
    const Eigen::Vector3d innovation(narrow->pose.x - job.predicted.x, narrow->pose.y - job.predicted.y,
                                     wrap_angle(narrow->pose.theta - job.predicted.theta));
    const Eigen::Matrix3d nominal = odometry_covariance(job.odom_relative);
    rb.odometry_trust.learn(innovation, job.cov, nominal);
    rb.odometry_calibration.learn(job.odom_motion, innovation.z(), job.cov(2, 2), nominal(2, 2));
    // A robot without a heading (v1) has its heading from its motion: it never drives backwards.
    if (job.keyframe.has_heading)
      rb.odometry_direction.learn(job.odom_motion,
                                  nodes_[*job.previous].estimate.inverse().compose(narrow->pose));
  }
  return CorrectionSource::Match;
}

PoseCorrector::TieDecision PoseCorrector::decide_tie(const MatchJob& job, const Robot& rb,
                                                     bool operator_set) {
  TieDecision decision;
  if (job.wide_skipped) ++stats_.wide_skipped;
  if (!job.tie || job.wide_skipped || operator_set || nodes_[job.anchor].removed) return decision;
  const Keyframe& keyframe = job.keyframe;
  const bool wide = job.wide;
  ++stats_.ties_tried;
  if (wide) ++stats_.closures_tried;
  const auto& tie = job.tie_match;
  if (!tie || tie->score < options_.closure_min_score) return decision;
  const Eigen::Matrix3d tie_cov = with_floor(tie->covariance, 0.02, 0.01);
  const ConsistencyCheck check;
  // A closure must be unambiguous (one clear peak: not a ring, a corridor or a row of identical
  // rooms) and agree with the uncertainty accumulated since the last tie.
  const bool distinct = (keyframe.scans ? options_.scan_distinct : options_.distinct).accepts(*tie);
  const bool consistent = check.accepts(job.estimate, tie->pose, rb.chain_cov + tie_cov);
  if (wide && !(distinct && consistent)) {
    ++stats_.closures_rejected;
    spdlog::debug("loop closure refused: robot {} keyframe {}, distinct {}, consistent {} ({})", rb.name,
                  keyframe.id, distinct, consistent, describe(*tie, keyframe.points.size(), rb.chain_cov));
    return decision;
  }
  decision.anchor = job.anchor;
  decision.estimate = tie->pose;
  decision.cov = tie_cov;
  if (wide) {
    const double moved_m = distance(tie->pose.position(), job.estimate.position());
    const double turned = wrap_angle(tie->pose.theta - job.estimate.theta);
    decision.closure = moved_m > 0.02 || std::abs(turned) > 0.005;
    ++stats_.closures_accepted;
    spdlog::info(
        "loop closure: robot {} keyframe {} moved {:.3f} m, {:.2f} deg against {} old keyframes ({})",
        rb.name, keyframe.id, moved_m, to_degrees(turned), job.neighbours,
        describe(*tie, keyframe.points.size(), rb.chain_cov));
  }
  return decision;
}

void PoseCorrector::confirm_relocalisation(const MatchJob& job, Robot& rb, TieDecision& tie) {
  const auto& found = job.relocalised;
  if (!job.relocalise || !found || nodes_[job.relocalise_anchor].removed) {
    rb.relocalise_hypothesis.reset();  // tight again, or a keyframe that did not find it
    rb.relocalise_agreed = 0;
    return;
  }
  const Keyframe& keyframe = job.keyframe;
  const bool agrees =
      rb.relocalise_hypothesis &&
      distance(rb.relocalise_hypothesis->compose(keyframe.odom).position(), found->pose.position()) <=
          options_.placement_agree_m &&
      std::abs(wrap_angle(rb.relocalise_hypothesis->compose(keyframe.odom).theta - found->pose.theta)) <=
          options_.placement_agree_rad;
  rb.relocalise_agreed = agrees ? rb.relocalise_agreed + 1 : 1;
  rb.relocalise_hypothesis = found->pose.compose(keyframe.odom.inverse());
  if (rb.relocalise_agreed < options_.relocalise_confirmations) return;
  rb.relocalise_hypothesis.reset();
  rb.relocalise_agreed = 0;
  tie.anchor = job.relocalise_anchor;
  tie.estimate = found->pose;
  tie.cov = with_floor(found->covariance, 0.02, 0.01);
  tie.closure = true;
  ++stats_.closures_tried;
  ++stats_.closures_accepted;
  spdlog::info(
      "loop closure by the trail: robot {} keyframe {} moved {:.2f} m, {:.1f} deg ({} points, score {:.2f}, "
      "pose sigma {:.2f} m)",
      rb.name, keyframe.id, distance(found->pose.position(), job.estimate.position()),
      to_degrees(wrap_angle(found->pose.theta - job.estimate.theta)), job.relocalise_points.size(),
      found->score, std::sqrt(std::max(rb.pose_cov(0, 0), rb.pose_cov(1, 1))));
}

Pose PoseCorrector::apply_tie(const Keyframe& keyframe, Robot& rb, const TieDecision& tie,
                              const Pose& estimate) {
  ++tied_since_optimise_;
  if (tie.closure) {
    bend_chain(keyframe.robot, keyframe.segment, estimate, tie.estimate);
    ++rb.state.loop_closures;
    closure_since_optimise_ = true;
    rb.chain_cov = tie.cov;
    rb.pose_cov = tie.cov;
    rb.heading_variance = tie.cov(2, 2);
    return tie.estimate;
  }
  // A tie inside the tracking window: the same update, weighted by what the robot has accumulated
  // since it was last tied.
  const Pose fused = fuse(estimate, rb.chain_cov, tie.estimate, tie.cov);
  rb.chain_cov = fused_covariance(rb.chain_cov, tie.cov);
  rb.pose_cov = fused_covariance(rb.pose_cov, tie.cov);
  rb.heading_variance = 1.0 / (1.0 / rb.heading_variance + 1.0 / tie.cov(2, 2));
  return fused;
}

Pose PoseCorrector::apply_operator_pose(const MatchJob& job, Robot& rb) {
  rb.chain_cov = diagonal(kOperatorSigma_m, kOperatorSigma_m, kOperatorSigma_rad);
  rb.pose_cov = rb.chain_cov;
  rb.heading_variance = kOperatorSigma_rad * kOperatorSigma_rad;
  return job.narrow ? job.narrow->pose : rb.operator_pose->compose(job.keyframe.odom);
}

uint32_t PoseCorrector::add_node_and_edges(MatchJob& job, const Robot& rb, const Pose& estimate,
                                           const Pose& tracked_motion, const TieDecision& tie,
                                           bool operator_set) {
  Keyframe& keyframe = job.keyframe;
  // A standing keyframe's node keeps no points: they repeat its previous keyframe's, and a robot
  // waiting for minutes would fill the nearest keyframes that matches and ties read with copies of
  // one view (its observations still go into the map as any others).
  if (job.standing) keyframe.points = {};
  if (options_.localise_only) return keep_latest_node(job, rb, estimate);
  const auto slot = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back(Node{keyframe.id, keyframe.robot, keyframe.segment, keyframe.first_stamp_ns, keyframe.odom,
                        estimate, std::move(keyframe.points), false});
  index_.insert(slot, estimate.position());
  if (job.previous) {
    // Tracking refines the odometry between consecutive keyframes, tied or not: a tie's or
    // closure's move is its own edge, not a motion. (Tied keyframes used to get the bare odometry
    // here, which the fused estimates did not follow; every optimisation then pulled the chains
    // towards it and moved robots that had closed nothing, by up to 15 cm.)
    if (job.narrow) {
      add_edge(EdgeKind::Sequential, *job.previous, slot, tracked_motion, with_floor(job.cov, 0.01, 0.005));
    } else {
      add_edge(EdgeKind::Sequential, *job.previous, slot, job.odom_relative, job.odom_cov);
    }
  }
  if (tie.anchor) {
    add_edge(EdgeKind::LoopClosure, *tie.anchor, slot,
             nodes_[*tie.anchor].estimate.inverse().compose(estimate), tie.cov);
  }
  if (job.wall_heading && !operator_set) {
    GraphEdge heading;
    heading.kind = EdgeKind::Heading;
    heading.from = heading.to = keyframe.id;
    heading.measurement = Pose{0.0, 0.0, *job.wall_heading};
    heading.information = Eigen::Matrix3d::Zero();
    heading.information(2, 2) = 1.0 / job.wall_variance;
    edges_.push_back(heading);
    ++stats_.wall_headings;
  }
  if (operator_set || !job.previous) {
    // A start, a new segment or an operator's pose: held where it was placed, as firmly as it is known.
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
  return slot;
}

uint32_t PoseCorrector::keep_latest_node(const MatchJob& job, const Robot& rb, const Pose& estimate) {
  const Keyframe& keyframe = job.keyframe;
  Node node{keyframe.id, keyframe.robot, keyframe.segment, keyframe.first_stamp_ns, keyframe.odom, estimate,
            {},          false};
  if (rb.last_node && !nodes_[*rb.last_node].removed) {
    nodes_[*rb.last_node] = std::move(node);
    return *rb.last_node;
  }
  nodes_.push_back(std::move(node));
  return static_cast<uint32_t>(nodes_.size() - 1);
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

void PoseCorrector::learn_wall_axes(const MatchJob& job, Robot& rb, const Pose& estimate) {
  if (job.wall_reading) {
    wall_axes_.learn(wrap_quarter(job.wall_reading->angle + estimate.theta));
    // At the pose given (the prediction from it, not a match's): the robot's first keyframes only.
    if (rb.anchors_walls > 0 && MapWallAxes::anchors(*job.wall_reading)) {
      wall_axes_.anchor(wrap_quarter(job.wall_reading->angle + job.predicted.theta), 1.0 / job.wall_variance);
    }
  }
  if (rb.anchors_walls > 0) --rb.anchors_walls;
}

void PoseCorrector::publish_keyframe(const MatchJob& job, Robot& rb, const Pose& estimate,
                                     CorrectionSource source, const TieDecision& tie,
                                     std::vector<KeyframeCorrection>& out) {
  const Keyframe& keyframe = job.keyframe;
  const Pose before = rb.state.map_from_odom.compose(keyframe.odom);
  rb.state.map_from_odom = estimate.compose(keyframe.odom.inverse());
  if (distance(before.position(), estimate.position()) > kJumpWarning_m) {
    spdlog::warn("pose correction: robot {} moved {:.2f} m by keyframe {} (tracked {}, tied {}, closure {})",
                 rb.name, distance(before.position(), estimate.position()), keyframe.id,
                 job.narrow.has_value(), tie.anchor.has_value(), tie.closure);
  }
  // How well the robot is known in the map, not this keyframe's measurement: exploring robots are
  // sent back to re-localise by it (the planner's LocalisationWatch).
  rb.state.covariance = rb.pose_cov;
  rb.state.segment = keyframe.segment;
  ++rb.state.keyframes;
  mark_changed(rb, source);
  out.push_back(
      KeyframeCorrection{keyframe.id, rb.name, keyframe.segment, keyframe.odom, rb.state.map_from_odom});
}

}  // namespace slam::correction
