// PoseCorrector: keyframes and their lifecycle (add, process, land). Matching is in
// pose_corrector_match.cpp, what a finished match does to the graph and to its robot's correction in
// pose_corrector_apply.cpp, the graph side in pose_corrector_graph.cpp, requests about one robot in
// pose_corrector_robots.cpp.
#include "pose_correction/pose_corrector.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "pose_correction/gaussian_pose.hpp"
#include "pose_correction/graph_optimizer.hpp"

namespace slam::correction {

PoseCorrector::PoseCorrector(const CorrectorOptions& options)
    : options_(options),
      matcher_(options.matcher),
      optimizer_(std::make_unique<GraphOptimizer>()),
      placement_searcher_(options),
      schedule_(options.schedule) {
  if (options.match_threads > 0) {
    // A finished job wakes the loop (set_wake): a robot's next keyframe waits for its last one's
    // match, so a loop passing only at its tick would finalise at most one keyframe per robot a tick.
    const auto wake = [this] {
      if (wake_) wake_();
    };
    worker_ = std::make_unique<MatchWorker>(
        options.matcher, [this](ScanMatcher& matcher, MatchJob& job) { match_keyframe(matcher, job); }, wake);
    placement_thread_ = std::make_unique<JobThread<PlacementJob>>(
        [this](PlacementJob& job) { placement_searcher_.run(job); }, wake);
  }
}

PoseCorrector::~PoseCorrector() = default;

uint32_t PoseCorrector::robot_index(std::string_view robot) {
  const std::string key(robot);
  if (auto it = robot_ids_.find(key); it != robot_ids_.end()) return it->second;
  const auto index = static_cast<uint32_t>(robots_.size());
  Robot robot_state(key, options_.keyframe);
  robot_state.state.robot = key;
  // Another robot maps already (or a restored or loaded map is there): where this one is must be
  // found before it draws anything. Only the first robot of an empty map starts it where its
  // odometry says.
  const bool map_exists = graph_keyframes() > 0 || !robots_.empty() || map_given_;
  if (options_.localise_only || (options_.global_localisation && map_exists)) {
    robot_state.state.placement = Placement::Unplaced;
    robot_state.state.localisation_score = 0.0;
  }
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
  stamp_ns = take_out_clock_steps(stamp_clock_, stamp_ns, "the observations' stamps");
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
  if (step == KeyframeBuilder::Step::Jump || step == KeyframeBuilder::Step::StartsNext) {
    if (rb.builder.open()) closed_.push_back(rb.builder.take());
    if (step == KeyframeBuilder::Step::Jump) ++stats_.segments;
    step = rb.builder.add(next_id_, r, stamp_ns, odom_pose, has_heading, hits, robot_stamp_ns);
  }
  const uint64_t id = rb.builder.open_id();
  if (id == next_id_) ++next_id_;
  if (step == KeyframeBuilder::Step::AddedAndClosed) closed_.push_back(rb.builder.take());
  return id;
}

int64_t PoseCorrector::take_out_clock_steps(ClockSteps& clock, int64_t t_ns, std::string_view what) {
  const int64_t offset = clock.offset_ns();
  const int64_t steady = clock(t_ns);
  if (clock.offset_ns() != offset) {
    ++stats_.clock_steps;
    spdlog::warn("pose correction: {} went back {:.0f} s: taken as a clock set back", what,
                 static_cast<double>(clock.offset_ns() - offset) * 1e-9);
  }
  return steady;
}

void PoseCorrector::process(const GridView& grid, int64_t now_ns, std::vector<KeyframeCorrection>& out) {
  now_ns = take_out_clock_steps(process_clock_, now_ns, "the time of process()");
  last_process_ns_ = now_ns;
  land(out);
  land_placement();
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
    if (Robot& owner = robots_[keyframe.robot]; owner.state.placement != Placement::Placed) {
      owner.held.push_back(std::move(keyframe));
      continue;
    }
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
  search_placements(grid, now_ns);
  for (Robot& rb : robots_)
    if (rb.state.placement != Placement::Placed) trim_held(rb, out);
  stats_.backlog = static_cast<int64_t>(closed_.size() + in_flight_);
  const bool due = closure_since_optimise_ || tied_since_optimise_ >= options_.optimise_every;
  if (options_.localise_only) return;  // a fixed map: nothing to optimise
  if ((finish_requested_ && closed_.empty() && in_flight_ == 0 && !optimising_) ||
      (due && schedule_.allow_optimisation(now_ns))) {
    finish_requested_ = false;
    start_optimisation();
  }
}

void PoseCorrector::finish() {
  for (Robot& rb : robots_) {
    if (rb.builder.open()) closed_.push_back(rb.builder.take());
    if (rb.state.placement != Placement::Placed) place(rb, std::nullopt, 0.0);  // not found: by odometry
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

}  // namespace slam::correction
