// PoseCorrector: keyframes and their lifecycle (add, process, land), and what a finished match does
// to the graph and to each robot's correction. Matching is in pose_corrector_match.cpp, the graph
// side in pose_corrector_graph.cpp, requests about one robot in pose_corrector_robots.cpp.
#include "pose_correction/pose_corrector.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "pose_correction/gaussian_pose.hpp"
#include "pose_correction/graph_optimizer.hpp"

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

PoseCorrector::PoseCorrector(const CorrectorOptions& options)
    : options_(options),
      matcher_(options.matcher),
      optimizer_(std::make_unique<GraphOptimizer>()),
      schedule_(options.schedule) {
  if (options.match_threads > 0) {
    worker_ = std::make_unique<MatchWorker>(
        options.matcher, [this](ScanMatcher& matcher, MatchJob& job) { match_keyframe(matcher, job); });
  }
}

PoseCorrector::~PoseCorrector() = default;

uint32_t PoseCorrector::robot_index(std::string_view robot) {
  const std::string key(robot);
  if (auto it = robot_ids_.find(key); it != robot_ids_.end()) return it->second;
  const auto index = static_cast<uint32_t>(robots_.size());
  Robot robot_state(key, options_.keyframe);
  robot_state.state.robot = key;
  robots_.push_back(std::move(robot_state));
  robot_ids_.emplace(key, index);
  return index;
}

Result<uint64_t> PoseCorrector::add(std::string_view robot, int64_t stamp_ns, const Pose& odom_pose,
                                    bool has_heading, std::span<const Vec2> hits,
                                    std::optional<int64_t> robot_stamp_ns) {
  const bool points_finite =
      std::all_of(hits.begin(), hits.end(), [](Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); });
  if (!is_finite(odom_pose) || !points_finite) {
    ++stats_.rejected_inputs;
    return Error{"observation has a non-finite pose or point"};
  }
  const uint32_t r = robot_index(robot);
  Robot& rb = robots_[r];
  rb.has_heading = has_heading;
  if (!rb.builder.has_last() && rb.state.keyframes == 0 && !rb.operator_pose &&
      norm(odom_pose.position()) > options_.far_start_m) {
    rb.state.map_from_odom = Pose{-odom_pose.x, -odom_pose.y, 0.0};
    mark_changed(rb, CorrectionSource::Identity);
    spdlog::info("pose correction: robot {} starts {:.0f} m from the map's origin: placed at the origin",
                 rb.name, norm(odom_pose.position()));
  }
  auto step = rb.builder.add(next_id_, r, stamp_ns, odom_pose, has_heading, hits, robot_stamp_ns);
  if (step == KeyframeBuilder::Step::Jump) {
    if (rb.builder.open()) closed_.push_back(rb.builder.take());
    ++stats_.segments;
    step = rb.builder.add(next_id_, r, stamp_ns, odom_pose, has_heading, hits, robot_stamp_ns);
  }
  const uint64_t id = rb.builder.open_id();
  if (id == next_id_) ++next_id_;
  if (step == KeyframeBuilder::Step::AddedAndClosed) closed_.push_back(rb.builder.take());
  return id;
}

void PoseCorrector::process(const GridView& grid, int64_t now_ns, std::vector<KeyframeCorrection>& out) {
  last_process_ns_ = now_ns;
  land(out);
  int64_t open_messages = 0;
  for (Robot& rb : robots_) {
    if (rb.builder.stale(now_ns)) closed_.push_back(rb.builder.take());
    open_messages += rb.builder.open_messages();
  }
  stats_.open_messages = open_messages;
  schedule_.begin_pass(closed_.size() + in_flight_, now_ns);
  stats_.load = static_cast<int64_t>(schedule_.load());
  size_t overflow = schedule_.overflow(closed_.size());
  int budget = schedule_.pass_budget();
  // In order; a keyframe whose robot has one in matching waits (its prediction needs that result),
  // and so does everything after the budget. The oldest ones past the backlog cap go by odometry.
  size_t kept = 0;
  for (size_t i = 0; i < closed_.size(); ++i) {
    Keyframe& keyframe = closed_[i];
    const bool waits = robots_[keyframe.robot].matching || (overflow == 0 && budget == 0);
    if (waits) {
      if (kept != i) closed_[kept] = std::move(keyframe);
      ++kept;
      continue;
    }
    const bool match = overflow == 0;
    if (match) {
      --budget;
    } else {
      --overflow;
    }
    start(std::move(keyframe), grid, match, out);
  }
  closed_.resize(kept);
  stats_.backlog = static_cast<int64_t>(closed_.size() + in_flight_);
  const bool due = closure_since_optimise_ || tied_since_optimise_ >= options_.optimise_every;
  if ((finish_requested_ && closed_.empty() && in_flight_ == 0 && !optimising_) ||
      (due && schedule_.allow_optimisation(now_ns))) {
    finish_requested_ = false;
    start_optimisation();
  }
}

void PoseCorrector::finish() {
  for (Robot& rb : robots_) {
    if (rb.builder.open()) closed_.push_back(rb.builder.take());
  }
  finish_requested_ = true;
}

std::unique_ptr<MatchJob> PoseCorrector::take_job() {
  if (spare_jobs_.empty()) return std::make_unique<MatchJob>();
  auto job = std::move(spare_jobs_.back());
  spare_jobs_.pop_back();
  return job;
}

void PoseCorrector::recycle(std::unique_ptr<MatchJob> job) {
  // Its buffers keep their capacity: the next keyframes allocate nothing for their grids.
  job->keyframe.points.clear();
  spare_jobs_.push_back(std::move(job));
}

void PoseCorrector::start(Keyframe&& keyframe, const GridView& grid, bool match,
                          std::vector<KeyframeCorrection>& out) {
  auto job = take_job();
  prepare(std::move(keyframe), grid, match, *job);
  if (!job->track) {
    ++(job->standing ? stats_.standing : stats_.placed_by_odometry);
    match_keyframe(matcher_, *job);  // matches nothing: sets the job's results to the prediction
  } else if (worker_) {
    robots_[job->keyframe.robot].matching = true;
    ++in_flight_;
    worker_->submit(std::move(job));
    return;
  } else {
    match_keyframe(matcher_, *job);
  }
  apply(*job, out);
  recycle(std::move(job));
}

void PoseCorrector::land(std::vector<KeyframeCorrection>& out) {
  if (!worker_) return;
  landed_.clear();
  worker_->take_done(landed_);
  for (auto& job : landed_) {
    --in_flight_;
    Robot& rb = robots_[job->keyframe.robot];
    rb.matching = false;
    if (job->generation == rb.generation) apply(*job, out);  // else the robot was reset meanwhile
    recycle(std::move(job));
  }
  landed_.clear();
}

Eigen::Matrix3d PoseCorrector::odometry_covariance(const Pose& relative) const {
  const double d = norm(relative.position());
  const double st = options_.odom_sigma_m_per_sqrt_m * std::sqrt(d) + 0.002;
  const double sr = options_.odom_sigma_rad_per_m * d + 0.01 * std::sqrt(std::abs(relative.theta)) + 0.002;
  return diagonal(st, st, sr);
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

void PoseCorrector::apply(MatchJob& job, std::vector<KeyframeCorrection>& out) {
  Keyframe& keyframe = job.keyframe;
  Robot& rb = robots_[keyframe.robot];
  ++stats_.keyframes;
  // An optimisation that landed while the keyframe was matched moved the robot's correction: move
  // what was matched with it.
  const Pose moved = rb.state.map_from_odom.compose(job.prepared_correction.inverse());
  auto carry = [&](Pose& p) { p = moved.compose(p); };
  carry(job.predicted);
  carry(job.tracked);
  carry(job.estimate);
  if (job.wall_heading) *job.wall_heading = wrap_angle(*job.wall_heading + moved.theta);
  if (job.narrow) carry(job.narrow->pose);
  if (job.tie_match) carry(job.tie_match->pose);
  const std::optional<uint32_t> previous = job.previous;
  const Pose odom_relative = job.odom_relative;
  const Eigen::Matrix3d odom_cov = job.odom_cov;

  Pose estimate = job.estimate;
  rb.heading_variance = job.heading_variance;
  // The motion from the previous keyframe as tracking measured it, before the walls' heading, a tie
  // or a closure moves this keyframe (a closure also bends the previous one): each of those is its
  // own edge.
  const Pose tracked_motion = previous ? nodes_[*previous].estimate.inverse().compose(job.tracked) : Pose{};
  Eigen::Matrix3d cov = job.narrow ? job.cov : rb.chain_cov;
  CorrectionSource source = rb.state.source;
  const auto& narrow = job.narrow;
  if (narrow) {
    source = CorrectionSource::Match;
    ++stats_.matched;
    if (job.point_refined) ++stats_.point_refined;
    // How far the match moved the odometry prediction teaches how far this robot's odometry holds.
    if (previous && narrow->flat_directions == 0) {
      const Eigen::Vector3d innovation(narrow->pose.x - job.predicted.x, narrow->pose.y - job.predicted.y,
                                       wrap_angle(narrow->pose.theta - job.predicted.theta));
      rb.odometry_trust.learn(innovation, job.cov, odometry_covariance(odom_relative));
    }
  } else if (!job.standing) {
    ++stats_.unmatched;
  }
  const bool tracked = narrow.has_value();

  std::optional<uint32_t> anchor;
  Pose anchored_estimate;
  Eigen::Matrix3d anchored_cov;
  bool closure = false;
  const bool operator_set = rb.operator_pose.has_value();
  if (job.wide_skipped) ++stats_.wide_skipped;
  if (job.tie && !job.wide_skipped && !operator_set && !nodes_[job.anchor].removed) {
    const bool wide = job.wide;
    ++stats_.ties_tried;
    if (wide) ++stats_.closures_tried;
    const auto& tie = job.tie_match;
    if (tie && tie->score >= options_.closure_min_score) {
      const Eigen::Matrix3d tie_cov = with_floor(tie->covariance, 0.02, 0.01);
      const ConsistencyCheck check;
      // A closure must be unambiguous (one clear peak: not a ring, a corridor or a row of identical
      // rooms) and agree with the uncertainty accumulated since the last tie.
      const bool distinct = (keyframe.scans ? options_.scan_distinct : options_.distinct).accepts(*tie);
      const bool consistent = check.accepts(estimate, tie->pose, rb.chain_cov + tie_cov);
      if (!wide || (distinct && consistent)) {
        anchor = job.anchor;
        anchored_estimate = tie->pose;
        anchored_cov = tie_cov;
        if (wide) {
          closure = distance(tie->pose.position(), estimate.position()) > 0.02 ||
                    std::abs(wrap_angle(tie->pose.theta - estimate.theta)) > 0.005;
          ++stats_.closures_accepted;
          spdlog::info(
              "loop closure: robot {} keyframe {} moved {:.3f} m, {:.2f} deg against {} old keyframes ({})",
              rb.name, keyframe.id, distance(tie->pose.position(), estimate.position()),
              to_degrees(wrap_angle(tie->pose.theta - estimate.theta)), job.neighbours,
              describe(*tie, keyframe.points.size(), rb.chain_cov));
        }
      } else {
        ++stats_.closures_rejected;
        spdlog::debug("loop closure refused: robot {} keyframe {}, distinct {}, consistent {} ({})", rb.name,
                      keyframe.id, distinct, consistent,
                      describe(*tie, keyframe.points.size(), rb.chain_cov));
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
      rb.pose_cov = anchored_cov;
      rb.heading_variance = anchored_cov(2, 2);
    } else {
      // A tie inside the tracking window: the same update, weighted by what the robot has
      // accumulated since it was last tied.
      estimate = fuse(estimate, rb.chain_cov, anchored_estimate, anchored_cov);
      rb.chain_cov = fused_covariance(rb.chain_cov, anchored_cov);
      rb.pose_cov = fused_covariance(rb.pose_cov, anchored_cov);
      rb.heading_variance = 1.0 / (1.0 / rb.heading_variance + 1.0 / anchored_cov(2, 2));
    }
    cov = anchored_cov;
    ++tied_since_optimise_;
  }
  if (operator_set) {
    estimate = rb.operator_pose->compose(keyframe.odom);
    if (tracked) estimate = narrow->pose;
    source = CorrectionSource::Operator;
    rb.chain_cov = diagonal(kOperatorSigma_m, kOperatorSigma_m, kOperatorSigma_rad);
    rb.pose_cov = rb.chain_cov;
    rb.heading_variance = kOperatorSigma_rad * kOperatorSigma_rad;
  }

  // 3. The node and its edges. A standing keyframe's node keeps no points: they repeat its previous
  // keyframe's, and a robot waiting for minutes would fill the nearest keyframes that matches and
  // ties read with copies of one view (its observations still go into the map as any others).
  if (job.standing) keyframe.points = {};
  const auto slot = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back(Node{keyframe.id, keyframe.robot, keyframe.segment, keyframe.first_stamp_ns, keyframe.odom,
                        estimate, std::move(keyframe.points), false});
  index_.insert(slot, estimate.position());
  if (previous) {
    // Tracking refines the odometry between consecutive keyframes, tied or not: a tie's or
    // closure's move is its own edge, not a motion. (Tied keyframes used to get the bare odometry
    // here, which the fused estimates did not follow; every optimisation then pulled the chains
    // towards it and moved robots that had closed nothing, by up to 15 cm.)
    if (tracked) {
      add_edge(EdgeKind::Sequential, *previous, slot, tracked_motion, with_floor(job.cov, 0.01, 0.005));
    } else {
      add_edge(EdgeKind::Sequential, *previous, slot, odom_relative, odom_cov);
    }
  }
  if (anchor) {
    add_edge(EdgeKind::LoopClosure, *anchor, slot, nodes_[*anchor].estimate.inverse().compose(estimate), cov);
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
  if (job.wall_reading) {
    wall_axes_.learn(wrap_quarter(job.wall_reading->angle + estimate.theta));
    // At the pose given (the prediction from it, not a match's): the robot's first keyframes only.
    if (rb.anchors_walls > 0 && MapWallAxes::anchors(*job.wall_reading)) {
      wall_axes_.anchor(wrap_quarter(job.wall_reading->angle + job.predicted.theta), 1.0 / job.wall_variance);
    }
  }
  if (rb.anchors_walls > 0) --rb.anchors_walls;
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

  if (keyframe_observer_) {
    const Node& node = nodes_[slot];
    keyframe_observer_(KeyframeDecision{rb.name, node.stamp_ns, node.odom, job.predicted,
                                        tracked ? std::optional<Pose>(narrow->pose) : std::nullopt,
                                        tracked ? narrow->covariance : Eigen::Matrix3d::Zero(),
                                        operator_set ? std::nullopt : job.wall_heading, estimate,
                                        anchor.has_value(), closure, rb.chain_cov});
  }
  const Pose before = rb.state.map_from_odom.compose(keyframe.odom);
  rb.state.map_from_odom = estimate.compose(keyframe.odom.inverse());
  if (distance(before.position(), estimate.position()) > kJumpWarning_m) {
    spdlog::warn("pose correction: robot {} moved {:.2f} m by keyframe {} (tracked {}, tied {}, closure {})",
                 rb.name, distance(before.position(), estimate.position()), keyframe.id, tracked,
                 anchor.has_value(), closure);
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
