// Recording a run's truth, poses and arrivals (see run_recorder.hpp).
#include "eval/run_recorder.hpp"

namespace slam::bench {

RunRecorder::RunRecorder(int64_t sample_period_ns, double reach_tolerance_m)
    : sample_period_ns_(sample_period_ns), waypoint_arrivals_(reach_tolerance_m) {}

void RunRecorder::start() {
  std::lock_guard lock(mutex_);
  sampling_ = true;
  next_sample_ns_ = -1;
}

void RunRecorder::stop() {
  std::lock_guard lock(mutex_);
  sampling_ = false;
}

void RunRecorder::on_truth(int64_t stamp_ns, const std::vector<RobotTruth>& robots) {
  std::lock_guard lock(mutex_);
  const bool sample = sampling_ && stamp_ns >= next_sample_ns_;
  if (sample) next_sample_ns_ = (next_sample_ns_ < 0 ? stamp_ns : next_sample_ns_) + sample_period_ns_;
  for (const RobotTruth& t : robots) {
    Robot& r = robots_[t.robot_id];
    const Vec2 truth = t.true_pose.position();
    if (!r.truth) {
      starts_.push_back(truth);
      r.first_truth_stamp_ns = stamp_ns;
    }
    r.truth = t;
    r.truth_stamp_ns = stamp_ns;
    for (GoalArrival& a : r.pending) {
      a.true_distance_m = distance(truth, a.waypoint);
      arrivals_.push_back(a);
    }
    r.pending.clear();
    if (!sample) continue;
    r.track.push_back(truth);
    const Vec2 corrected = r.correction.compose(t.reported_pose).position();
    samples_.push_back({t.robot_id, truth, t.reported_pose.position(), corrected});
    if (r.placed) placed_samples_.push_back(samples_.back());
    truth_samples_.push_back({stamp_ns, t});
    if (r.state) published_.emplace_back(*r.state, truth);
  }
}

void RunRecorder::on_published_pose(const std::string& robot_id, Vec2 map_position) {
  std::lock_guard lock(mutex_);
  robots_[robot_id].state = map_position;
}

void RunRecorder::on_correction(const std::string& robot_id, const Pose& map_from_odom, uint64_t version,
                                bool loop, bool placed) {
  std::lock_guard lock(mutex_);
  Robot& r = robots_[robot_id];
  if (placed && !r.placed && r.truth) {
    r.placed = true;
    placements_.push_back(
        {robot_id, static_cast<double>(r.truth_stamp_ns - r.first_truth_stamp_ns) * 1e-9,
         distance(map_from_odom.compose(r.truth->reported_pose).position(), r.truth->true_pose.position())});
  }
  // Version 0 is "never corrected", the identity: the first change (version 1) replaces it.
  const bool previous_known = version > r.correction_version && (r.correction_version > 0 || version == 1);
  if (previous_known && r.truth)
    changes_.push_back({robot_id, version, r.truth_stamp_ns, loop, r.correction, map_from_odom,
                        r.truth->reported_pose, r.truth->true_pose.position(),
                        version - r.correction_version - 1});
  else
    ++unscored_corrections_;
  r.correction = map_from_odom;
  r.correction_version = version;
}

void RunRecorder::on_path(const std::string& robot_id, const PathView& path) {
  std::lock_guard lock(mutex_);
  Robot& r = robots_[robot_id];
  for (const Vec2& w : waypoint_arrivals_.update(robot_id, path, r.state)) {
    if (!sampling_) continue;
    r.pending.push_back({robot_id, w, 0.0, r.state ? distance(*r.state, w) : 0.0});
  }
}

std::vector<TrajectorySample> RunRecorder::samples() const {
  std::lock_guard lock(mutex_);
  return samples_;
}

std::vector<TruthSample> RunRecorder::truth_samples() const {
  std::lock_guard lock(mutex_);
  return truth_samples_;
}

std::vector<std::pair<Vec2, Vec2>> RunRecorder::published_vs_truth() const {
  std::lock_guard lock(mutex_);
  return published_;
}

std::vector<GoalArrival> RunRecorder::arrivals() const {
  std::lock_guard lock(mutex_);
  return arrivals_;
}

std::vector<Vec2> RunRecorder::true_starts() const {
  std::lock_guard lock(mutex_);
  return starts_;
}

std::map<std::string, std::vector<Vec2>> RunRecorder::true_tracks() const {
  std::lock_guard lock(mutex_);
  std::map<std::string, std::vector<Vec2>> out;
  for (const auto& [id, r] : robots_) out[id] = r.track;
  return out;
}

std::vector<CorrectionChange> RunRecorder::correction_changes() const {
  std::lock_guard lock(mutex_);
  return changes_;
}

size_t RunRecorder::unscored_corrections() const {
  std::lock_guard lock(mutex_);
  return unscored_corrections_;
}

size_t RunRecorder::robots_seen() const {
  std::lock_guard lock(mutex_);
  size_t n = 0;
  for (const auto& [id, r] : robots_) n += r.truth ? 1 : 0;
  return n;
}

size_t RunRecorder::robots_published() const {
  std::lock_guard lock(mutex_);
  size_t n = 0;
  for (const auto& [id, r] : robots_) n += r.state ? 1 : 0;
  return n;
}

std::vector<RobotPlacement> RunRecorder::placements() const {
  std::lock_guard lock(mutex_);
  return placements_;
}

std::vector<TrajectorySample> RunRecorder::placed_samples() const {
  std::lock_guard lock(mutex_);
  return placed_samples_;
}

size_t RunRecorder::corrected_robots() const {
  std::lock_guard lock(mutex_);
  size_t n = 0;
  for (const auto& [id, r] : robots_) n += r.correction_version > 0 ? 1 : 0;
  return n;
}

}  // namespace slam::bench
