// The pose-graph side of PoseCorrector: bending a robot's recent chain after a loop closure,
// submitting the graph to the background optimiser and applying what it returns.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <optional>
#include <unordered_map>

#include "pose_correction/graph_optimizer.hpp"
#include "pose_correction/pose_corrector.hpp"

namespace slam::correction {

namespace {

constexpr double kMovedEpsilon_m = 0.001;  // smaller keyframe moves are not reported
constexpr double kClosureLossScale = 3.0;  // Cauchy scale (sigmas) of tie and closure edges

}  // namespace

void PoseCorrector::bend_chain(uint32_t robot, uint32_t segment, const Pose& from, const Pose& to) {
  // The keyframes since the robot was last tied to the map drifted along with it: spread the
  // closure's correction over them (none at the tie, all of it at the closing keyframe), rotating
  // about the closing position. The optimiser starts from a graph that already agrees with the
  // closure instead of one whose stiff recent chain would pull the robot back.
  Robot& rb = robots_[robot];
  const uint32_t first = rb.last_tied ? *rb.last_tied + 1 : 0;
  std::vector<uint32_t>& chain = neighbours_;
  chain.clear();
  for (uint32_t slot = first; slot < nodes_.size(); ++slot) {
    const Node& n = nodes_[slot];
    if (n.robot == robot && n.segment == segment && !n.removed) chain.push_back(slot);
  }
  const Vec2 centre = from.position();
  const Vec2 shift = to.position() - from.position();
  const double turn = wrap_angle(to.theta - from.theta);
  for (size_t i = 0; i < chain.size(); ++i) {
    Node& n = nodes_[chain[i]];
    const double f = static_cast<double>(i + 1) / static_cast<double>(chain.size() + 1);
    const Pose rotate{0.0, 0.0, f * turn};
    const Vec2 p = centre + rotate.transform(n.estimate.position() - centre) + shift * f;
    n.estimate = Pose{p.x, p.y, wrap_angle(n.estimate.theta + f * turn)};
    pending_moved_.push_back({n.id, rb.name, n.segment, n.odom, n.estimate.compose(n.odom.inverse())});
    pending_shift_ = std::max(pending_shift_, norm(shift) * f);
  }
  ++epoch_;  // an optimisation running now started from the unbent chain: its result is stale
}

void PoseCorrector::start_optimisation() {
  if (optimising_) return;
  PoseGraph graph;
  bool any_fixed = false;
  for (const Node& n : nodes_) {
    if (n.removed) continue;
    (void)graph.add_node(n.id, n.estimate, n.fixed);
    any_fixed = any_fixed || n.fixed;
  }
  bool any_prior = any_fixed;
  for (const GraphEdge& e : edges_) {
    any_prior = any_prior || e.kind == EdgeKind::Prior;
    (void)graph.add_edge(e);
  }
  if (!any_prior) {
    const auto live = std::find_if(nodes_.begin(), nodes_.end(), [](const Node& n) { return !n.removed; });
    if (live != nodes_.end()) (void)graph.set_fixed(live->id, true);
  }
  submitted_estimates_.clear();
  for (const Node& n : nodes_) submitted_estimates_.push_back(n.estimate);
  submitted_nodes_ = nodes_.size();
  OptimiseOptions solve;
  solve.loop_closure_loss_scale = kClosureLossScale;
  optimizer_->submit(std::move(graph), solve);
  submitted_epoch_ = epoch_;
  submitted_ns_ = last_process_ns_;
  optimising_ = true;
  ++stats_.optimisations;
  tied_since_optimise_ = 0;
  closure_since_optimise_ = false;
}

double PoseCorrector::take_optimised(std::vector<KeyframeCorrection>& moved) {
  // Keyframes a closure bent since the last call.
  double max_shift = pending_shift_;
  moved.insert(moved.end(), pending_moved_.begin(), pending_moved_.end());
  pending_moved_.clear();
  pending_shift_ = 0.0;
  if (!optimising_) return max_shift;
  auto landed = optimizer_->take_result();
  if (!landed) return max_shift;
  optimising_ = false;
  schedule_.optimisation_landed(submitted_ns_, last_process_ns_);
  if (!landed->status) {
    ++stats_.failed_optimisations;
    return max_shift;
  }
  if (submitted_epoch_ != epoch_) {
    closure_since_optimise_ = true;  // solve again from the current graph at the next process()
    return max_shift;
  }
  std::unordered_map<NodeId, Pose> optimised;
  optimised.reserve(landed->estimates.size());
  for (const NodeEstimate& e : landed->estimates) optimised.emplace(e.id, e.pose);
  // Per robot: how its newest submitted keyframe moved, applied to keyframes made since.
  std::vector<std::optional<Pose>> robot_delta(robots_.size());
  for (size_t i = 0; i < submitted_nodes_; ++i) {
    Node& n = nodes_[i];
    const auto it = optimised.find(n.id);
    if (it == optimised.end() || n.removed) continue;
    const Pose before = submitted_estimates_[i];
    robot_delta[n.robot] = it->second.compose(before.inverse());
    const Pose current = n.estimate;
    n.estimate = it->second;
    const double shift = distance(current.position(), n.estimate.position());
    if (shift > kMovedEpsilon_m) {
      max_shift = std::max(max_shift, shift);
      moved.push_back({n.id, robots_[n.robot].name, n.segment, n.odom, n.estimate.compose(n.odom.inverse())});
    }
  }
  for (size_t i = submitted_nodes_; i < nodes_.size(); ++i) {
    Node& n = nodes_[i];
    if (!robot_delta[n.robot] || n.removed) continue;
    const Pose current = n.estimate;
    n.estimate = robot_delta[n.robot]->compose(n.estimate);
    const double shift = distance(current.position(), n.estimate.position());
    max_shift = std::max(max_shift, shift);
    moved.push_back({n.id, robots_[n.robot].name, n.segment, n.odom, n.estimate.compose(n.odom.inverse())});
  }
  for (size_t r = 0; r < robots_.size(); ++r) {
    if (!robot_delta[r]) continue;
    Robot& rb = robots_[r];
    const Vec2 corrected = rb.state.map_from_odom.transform(rb.builder.last_odom().position());
    const double move = distance(robot_delta[r]->transform(corrected), corrected);
    if (move > kJumpWarning_m) {
      spdlog::warn("pose correction: robot {} moved {:.2f} m by a graph optimisation", rb.name, move);
    } else {
      spdlog::debug("graph optimisation moved robot {} by {:.3f} m", rb.name, move);
    }
    rb.state.map_from_odom = robot_delta[r]->compose(rb.state.map_from_odom);
    mark_changed(rb, CorrectionSource::Loop);
  }
  rebuild_index();
  return max_shift;
}

void PoseCorrector::wait_for_optimisation() const {
  while (!optimizer_->wait_idle(std::chrono::seconds(1))) {
  }
}

void PoseCorrector::rebuild_index() {
  index_.clear();
  for (uint32_t slot = 0; slot < nodes_.size(); ++slot) {
    if (!nodes_[slot].removed) index_.insert(slot, nodes_[slot].estimate.position());
  }
}

}  // namespace slam::correction
