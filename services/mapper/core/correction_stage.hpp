#pragma once
// Between the observation stream and the Mapper: each raw observation (robot odometry frame) goes to
// the SLAM core (PoseCorrector) and waits here until its keyframe is matched and finalised; then it
// reaches the Mapper with that keyframe's correction and id, so the grid gets it in the map frame
// and the store keeps it raw. Holding it back matters: a keyframe matched against a map that
// already holds its own points would only confirm its predicted pose.
// After a pose-graph optimisation the moved keyframes are stored and the grid is re-rendered.
// With SLAM off, observations pass straight through with the identity (today's behaviour).
// Localising only (CorrectorOptions::localise_only) the map stays as loaded: observations only
// place and track their robots; none is drawn or stored, and neither are the keyframes.
// Plain C++; the mapper's loop thread calls everything (the corrector may match on its own worker:
// a keyframe's observations then reach the grid at a later step()).
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "common/core/log.hpp"
#include "common/core/result.hpp"
#include "mapper/core/mapper.hpp"
#include "pose_correction/pose_corrector.hpp"

namespace slam::mapper {

class CorrectionStage {
 public:
  CorrectionStage(bool enabled, const correction::CorrectorOptions& options);

  // Hands the stored keyframes to the corrector, so corrections continue where they were.
  Status restore(Mapper& mapper);

  // One raw observation (`scan.keyframe_id` and `scan.map_from_odom` are set here).
  void add(Mapper& mapper, const RobotScan& scan, int64_t now_mono_ns);
  // Matches the keyframes that closed, hands their observations to the mapper, and applies a
  // finished optimisation. `now_ns`: the observations' clock (Unix epoch).
  void step(Mapper& mapper, int64_t now_ns, int64_t now_mono_ns);

  // An operator's initial pose. Errors (MapError): UnknownRobot for a robot not heard from yet,
  // else InvalidRequest (not finite, outside the map, SLAM off).
  Status set_initial_pose(const Mapper& mapper, std::string_view robot, const Pose& map_pose);
  // An operator's answer to where a robot is being placed (PoseCorrector::answer_placement). Errors
  // (MapError): UnknownRobot for a robot not heard from yet, else InvalidRequest (nothing to accept
  // or reject, SLAM off).
  Status answer_placement(std::string_view robot, bool accept);
  // An operator's robot reset: its keyframes leave the pose graph and index, and its observations
  // still waiting for a keyframe are dropped (the store forgets the robot's older ones). Returns
  // how many keyframes left the graph.
  size_t reset_robot(std::string_view robot);
  // Robots whose correction changed since the last call.
  void take_changed(std::vector<correction::RobotCorrection>& out);
  // Closes the open keyframes and optimises the whole graph at the next steps (PoseCorrector::finish).
  void finish() { corrector_.finish(); }
  bool enabled() const { return enabled_; }
  bool knows(std::string_view robot) const { return corrector_.knows(robot); }
  // Whether a pose-graph optimisation is running or waiting to be applied by step().
  bool optimising() const { return corrector_.optimising(); }
  void wait_for_optimisation() const { corrector_.wait_for_optimisation(); }
  const correction::CorrectorStats& stats() const { return corrector_.stats(); }
  // Runs on a worker thread when a keyframe's match (or a placement search) is done: wakes the loop
  // to step() again. Set it before the first step().
  void set_wake(std::function<void()> wake) { corrector_.set_wake(std::move(wake)); }
  void set_keyframe_observer(std::function<void(const correction::KeyframeDecision&)> observer) {
    corrector_.set_keyframe_observer(std::move(observer));
  }
  // Observations held back until their keyframe is finalised (stats().open_messages of them wait
  // for their keyframe to close; the rest for its match).
  int64_t held_observations() const { return held_observations_; }
  // Observations of unplaced and lost robots' keyframes dropped while they were searched for (never drawn).
  int64_t dropped_observations() const { return dropped_observations_; }
  // Localising only: observations that placed and tracked their robots (none is drawn).
  int64_t localised_observations() const { return localised_observations_; }

 private:
  using Held = OwnedObservation;  // an observation waiting for its keyframe

  void save(Mapper& mapper, std::span<const correction::KeyframeCorrection> keyframes);
  // Starts the re-render an optimisation asked for, once the last one is far enough behind.
  void rerender_when_due(Mapper& mapper, int64_t now_mono_ns);

  bool enabled_;
  bool localise_only_;
  double rerender_shift_m_;
  correction::PoseCorrector corrector_;
  std::unordered_map<uint64_t, std::vector<Held>> held_;  // keyframe id -> its observations, in order
  std::vector<Held> spare_;                               // records to reuse
  int64_t held_observations_ = 0;                         // in held_
  int64_t dropped_observations_ = 0;
  int64_t localised_observations_ = 0;
  bool rerender_due_ = false;                   // keyframes moved since the last re-render
  std::optional<int64_t> rerender_started_ns_;  // the running re-render's start (monotonic)
  int64_t next_rerender_ns_ = std::numeric_limits<int64_t>::min();
  std::vector<correction::KeyframeCorrection> finalised_;
  std::vector<correction::KeyframeCorrection> moved_;
  std::vector<Keyframe> keyframes_;
  RateLimitedLog log_;
};

}  // namespace slam::mapper
