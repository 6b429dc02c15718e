// Replaying recorded observations through the mapper's map loop (replay.hpp).
#include "eval/replay.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <string>

#include "mapper/core/correction_stage.hpp"
#include "mapper/core/map_files.hpp"
#include "mapper/core/observation_store.hpp"
#include "temp_dir.hpp"

namespace slam::bench {

namespace {

constexpr int64_t kLoopPeriodNs = 100'000'000;  // the mapper's patch period: one loop pass

// Logs each robot's corrected error (distance and map-frame vector) and raw error at one truth instant
// (`since_ns` after the first observation), among the pose correction's own log lines.
void trace(std::span<const RobotTruth> instant, const std::map<std::string, Pose>& corrections,
           int64_t since_ns) {
  for (const RobotTruth& t : instant) {
    const auto c = corrections.find(t.robot_id);
    const Pose correction = c == corrections.end() ? Pose{} : c->second;
    const Vec2 corrected = correction.compose(t.reported_pose).position();
    const Vec2 error = corrected - t.true_pose.position();
    spdlog::info("trace {:.1f} s {} error {:.3f} m ({:+.3f}, {:+.3f}), raw {:.3f} m",
                 static_cast<double>(since_ns) * 1e-9, t.robot_id, norm(error), error.x, error.y,
                 distance(t.reported_pose.position(), t.true_pose.position()));
  }
}

// The truth of `robot` at the first sampled instant at or after `stamp_ns` (null past the last).
const RobotTruth* truth_at(std::span<const TruthSample> truth, std::string_view robot, int64_t stamp_ns) {
  auto it = std::lower_bound(truth.begin(), truth.end(), stamp_ns,
                             [](const TruthSample& s, int64_t stamp) { return s.stamp_ns < stamp; });
  for (; it != truth.end(); ++it)
    if (it->truth.robot_id == robot) return &it->truth;
  return nullptr;
}

// Logs where one keyframe was predicted, matched and placed against its true pose: the true
// map-from-odometry transform of that instant applied to the keyframe's odometry origin. A match
// that agrees with the prediction while both are off means the map there was built off.
void trace_keyframe(const correction::KeyframeDecision& k, std::span<const TruthSample> truth, int64_t t0) {
  const RobotTruth* t = truth_at(truth, k.robot, k.stamp_ns);
  if (!t) return;
  const Pose truth_pose = t->true_pose.compose(t->reported_pose.inverse()).compose(k.odom);
  auto error = [&](const Pose& p) {
    const Vec2 e = p.position() - truth_pose.position();
    return fmt::format("{:.1f} cm ({:+.1f}, {:+.1f}) {:+.2f} deg", 100 * norm(e), 100 * e.x, 100 * e.y,
                       to_degrees(wrap_angle(p.theta - truth_pose.theta)));
  };
  const char* tie = k.closure ? ", loop closure" : k.tied ? ", tied" : "";
  const std::string walls =
      k.wall_heading ? fmt::format("{:+.2f} deg", to_degrees(wrap_angle(*k.wall_heading - truth_pose.theta)))
                     : std::string("none");
  spdlog::info(
      "keyframe {:.1f} s {} at ({:.2f}, {:.2f}): predicted {}, match {} (sigma {:.1f} / {:.1f} cm, {:.2f} "
      "deg), walls {}, placed {}{}, uncertainty {:.1f} cm",
      static_cast<double>(k.stamp_ns - t0) * 1e-9, k.robot, truth_pose.x, truth_pose.y, error(k.predicted),
      k.match ? error(*k.match) : std::string("none"), 100 * std::sqrt(k.match_covariance(0, 0)),
      100 * std::sqrt(k.match_covariance(1, 1)), to_degrees(std::sqrt(k.match_covariance(2, 2))), walls,
      error(k.estimate), tie, 100 * std::sqrt(k.uncertainty(0, 0) + k.uncertainty(1, 1)));
}

}  // namespace

Result<std::vector<mapper::OwnedObservation>> read_observations(const std::filesystem::path& store) {
  if (!std::filesystem::exists(store)) return Error{"no recording " + store.string()};
  auto opened = mapper::ObservationStore::open(store);
  if (!opened) return opened.error();
  std::vector<mapper::OwnedObservation> out;
  SLAM_TRY(opened->for_each([&](const mapper::ObservationRecord& r) {
    out.emplace_back().assign(r.robot_id, r.seq, r.stamp_ns, r.obs, r.robot_stamp_ns);
  }));
  if (out.empty()) return Error{store.string() + " holds no observation"};
  return out;
}

Result<std::unique_ptr<DeterministicMapLoop>> DeterministicMapLoop::create(
    const correction::CorrectorOptions& slam) {
  std::unique_ptr<DeterministicMapLoop> loop(new DeterministicMapLoop());
  loop->dir_ = std::make_unique<testkit::TempDir>("eval-replay");
  mapper::MapperOptions mapper_options;
  loop->store_path_ = loop->dir_->path() / "map.db";
  mapper_options.store = loop->store_path_.string();
  auto made = mapper::Mapper::create(mapper_options, loop->counters_, 1, [] {});
  if (!made) return made.error();
  loop->map_ = std::move(*made);
  correction::CorrectorOptions options = slam;
  options.match_threads = 0;  // inline: deterministic
  loop->stage_ = std::make_unique<mapper::CorrectionStage>(true, options);
  return loop;
}

DeterministicMapLoop::~DeterministicMapLoop() {
  stage_.reset();
  map_.reset();  // commits the store before its directory goes
}

void DeterministicMapLoop::add(const mapper::OwnedObservation& o, int64_t mono_ns) {
  stage_->add(*map_, mapper::RobotScan{o.robot_id, o.seq, o.stamp_ns, o.view(), 0, Pose{}, o.robot_stamp_ns},
              mono_ns);
}

void DeterministicMapLoop::step(int64_t tick_ns, int64_t mono_ns,
                                std::vector<correction::RobotCorrection>& changed) {
  map_->poll_rebuild();
  stage_->step(*map_, tick_ns, mono_ns);
  // Optimisations and re-renders land within this pass, whatever their time.
  map_->wait_for_rebuild();
  while (stage_->optimising()) {
    stage_->wait_for_optimisation();
    stage_->step(*map_, tick_ns, mono_ns);
    map_->wait_for_rebuild();
  }
  map_->commit();
  stage_->take_changed(changed);
}

void DeterministicMapLoop::finish(int64_t tick_ns, int64_t mono_ns,
                                  std::vector<correction::RobotCorrection>& changed) {
  stage_->finish();
  step(tick_ns, mono_ns, changed);  // matches the keyframes finish() closed, then optimises and applies
}

Result<ReplayOutcome> replay(std::span<const mapper::OwnedObservation> observations,
                             std::span<const TruthSample> truth, const ReplayOptions& options,
                             RunRecorder& recorder, const std::filesystem::path& yaml_path) {
  if (observations.empty()) return Error{"nothing to replay: no observation"};
  correction::CorrectorOptions slam_options;
  const mapper::MapperOptions mapper_defaults;
  slam_options.old_age_s = mapper_defaults.slam_old_age_s;
  slam_options.wall_heading = options.wall_heading;
  slam_options.point_refine = options.point_refine;
  slam_options.odometry_calibration = options.odometry_calibration;
  auto made = DeterministicMapLoop::create(slam_options);
  if (!made) return made.error();
  DeterministicMapLoop& loop = **made;
  mapper::Mapper& map = loop.map();
  mapper::CorrectionStage& stage = loop.stage();

  if (options.trace_keyframes)
    stage.set_keyframe_observer([&](const correction::KeyframeDecision& k) {
      trace_keyframe(k, truth, observations.front().stamp_ns);
    });

  recorder.start();
  const auto wall0 = std::chrono::steady_clock::now();
  const int64_t t0 = observations.front().stamp_ns;
  size_t next_obs = 0, next_truth = 0;
  std::vector<correction::RobotCorrection> changed;
  std::vector<RobotTruth> instant;
  std::map<std::string, Pose> corrections;  // each robot's latest, for the trace
  for (int64_t tick = t0 + kLoopPeriodNs + static_cast<int64_t>(options.phase_ms * 1e6);
       next_obs < observations.size() || next_truth < truth.size(); tick += kLoopPeriodNs) {
    const int64_t mono = tick - t0;
    for (; next_obs < observations.size() && observations[next_obs].stamp_ns <= tick; ++next_obs)
      loop.add(observations[next_obs], mono);
    changed.clear();
    loop.step(tick, mono, changed);
    for (const auto& c : changed) {
      recorder.on_correction(c.robot, c.map_from_odom, c.version,
                             c.source == correction::CorrectionSource::Loop,
                             c.placement == correction::Placement::Placed);
      corrections[c.robot] = c.map_from_odom;
    }
    while (next_truth < truth.size() && truth[next_truth].stamp_ns <= tick) {
      const int64_t stamp = truth[next_truth].stamp_ns;
      instant.clear();
      for (; next_truth < truth.size() && truth[next_truth].stamp_ns == stamp; ++next_truth)
        instant.push_back(truth[next_truth].truth);
      recorder.on_truth(stamp, instant);
      if (options.trace) trace(instant, corrections, stamp - t0);
    }
  }
  recorder.stop();
  ReplayOutcome outcome;
  outcome.stats = stage.stats();
  outcome.recorded_s = static_cast<double>(observations.back().stamp_ns - t0) * 1e-9;
  outcome.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const mapper::FileOutcome exported = mapper::export_map_file(map.grid(), yaml_path.string());
  if (!exported.ok()) return Error{"map export: " + exported.message};
  return outcome;
}

}  // namespace slam::bench
