#pragma once
// What a mapping run is scored by, live (eval_mapping) or replayed (eval_replay): the trajectory
// error of the corrected and raw poses, the exported map against the true walls, the coverage of
// the reachable space and the loop-closure audit, plus the run's picture (the map with the robots'
// true tracks and the true walls over it).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>

#include "common/core/map_io.hpp"
#include "common/core/result.hpp"
#include "eval/closure_audit.hpp"
#include "eval/map_metrics.hpp"
#include "eval/run_recorder.hpp"
#include "eval/trajectory_metrics.hpp"

namespace slam::bench {

struct ScoreOptions {
  bool align = false;                      // fit the map frame to the world first (trajectory_errors)
  double false_closure_increase_m = 0.10;  // a loop correction adding more error than this is false
  int pixels_per_cell = 2;
};

struct RunScore {
  TrajectoryErrors ate;
  WallScores walls;
  CoverageScore coverage;
  ClosureAudit closures;
  double resolution_m = 0.0;
};

// Scores the run `recorder` holds against `world_walls` (world frame) and writes its picture to `png`.
Result<RunScore> score_run(const RunRecorder& recorder, const MapImage& map,
                           std::span<const sim::Segment> world_walls, const ScoreOptions& options,
                           const std::filesystem::path& png);

nlohmann::json to_json(const ErrorStats& s);
// The score's fields of a run's JSON: ate_corrected, ate_raw, map, closures, alignment.
void add_to_json(const RunScore& score, const RunRecorder& recorder, const ScoreOptions& options,
                 nlohmann::json& out);

}  // namespace slam::bench
