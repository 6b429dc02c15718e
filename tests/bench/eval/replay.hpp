#pragma once
// The mapper's map loop with pose correction (Mapper + CorrectionStage, no DDS) run over recorded
// observations, deterministically: the loop steps every 100 ms of the observations' own clock, as
// the mapper's does, but keyframes are matched inline and every optimisation and re-render is
// waited for, so the same input gives the same corrections every time. What eval_replay runs.
#include <filesystem>
#include <span>

#include "common/core/result.hpp"
#include "eval/run_recorder.hpp"
#include "mapper/core/correction_stage.hpp"
#include "mapper/core/mapper.hpp"
#include "pose_correction/pose_corrector.hpp"
#include "temp_dir.hpp"

namespace slam::bench {

struct ReplayOptions {
  double phase_ms = 0.0;  // the loop's first pass this long after the first observation (+ one period)
  bool trace = false;     // log (info) every robot's corrected and raw error at every truth instant
  // Log (info) every keyframe's predicted, matched and placed pose against the truth of its instant.
  bool trace_keyframes = false;
  bool wall_heading = true;          // CorrectorOptions::wall_heading (the mapper's --slam-wall-heading)
  bool point_refine = true;          // CorrectorOptions::point_refine (the mapper's --slam-point-refine)
  bool odometry_calibration = true;  // CorrectorOptions::odometry_calibration
};

struct ReplayOutcome {
  correction::CorrectorStats stats;
  double recorded_s = 0.0;  // from the first observation to the last
  double wall_s = 0.0;
};

// The mapper's map loop (Mapper + CorrectionStage over a temporary store) stepped deterministically:
// keyframes are matched inline and every optimisation and re-render is waited for within the pass.
// What replay() and eval_log run.
class DeterministicMapLoop {
 public:
  static Result<std::unique_ptr<DeterministicMapLoop>> create(const correction::CorrectorOptions& slam);
  ~DeterministicMapLoop();

  // One raw observation (robot odometry frame); `mono_ns`: the loop's monotonic clock.
  void add(const mapper::OwnedObservation& observation, int64_t mono_ns);
  // One pass at `tick_ns` (the observations' clock): corrections that changed are appended.
  void step(int64_t tick_ns, int64_t mono_ns, std::vector<correction::RobotCorrection>& changed);
  // A last optimisation of the whole graph, applied (its corrections appended), as a mapper does
  // before a trajectory is exported from a finished run.
  void finish(int64_t tick_ns, int64_t mono_ns, std::vector<correction::RobotCorrection>& changed);

  mapper::Mapper& map() { return *map_; }
  mapper::CorrectionStage& stage() { return *stage_; }
  const std::filesystem::path& store_path() const { return store_path_; }

 private:
  DeterministicMapLoop() = default;
  std::unique_ptr<testkit::TempDir> dir_;
  std::filesystem::path store_path_;
  Counters counters_;
  std::unique_ptr<mapper::Mapper> map_;
  std::unique_ptr<mapper::CorrectionStage> stage_;
};

// Replays `observations` (in arrival order) and feeds `recorder` every correction change and every
// truth sample (`truth` in stamp order) as a live run would; `recorder` is started and stopped
// here. At the end the grid is exported as a ROS map to `yaml_path` (its directory must exist).
Result<ReplayOutcome> replay(std::span<const mapper::OwnedObservation> observations,
                             std::span<const TruthSample> truth, const ReplayOptions& options,
                             RunRecorder& recorder, const std::filesystem::path& yaml_path);

// Every observation of a mapper store, in insertion (arrival) order.
Result<std::vector<mapper::OwnedObservation>> read_observations(const std::filesystem::path& store);

}  // namespace slam::bench
