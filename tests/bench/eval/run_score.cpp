// Scoring a mapping run (run_score.hpp).
#include "eval/run_score.hpp"

#include "eval/map_overlay.hpp"

namespace slam::bench {

namespace {

std::vector<sim::Segment> moved(std::span<const sim::Segment> segments, const Pose& transform) {
  std::vector<sim::Segment> out;
  out.reserve(segments.size());
  for (const sim::Segment& s : segments) out.push_back({transform.transform(s.a), transform.transform(s.b)});
  return out;
}

std::vector<sim::Segment> polyline(const std::vector<Vec2>& points, const Pose& transform) {
  std::vector<sim::Segment> out;
  for (size_t i = 1; i < points.size(); ++i)
    out.push_back({transform.transform(points[i - 1]), transform.transform(points[i])});
  return out;
}

}  // namespace

Result<RunScore> score_run(const RunRecorder& recorder, const MapImage& map,
                           std::span<const sim::Segment> world_walls, const ScoreOptions& options,
                           const std::filesystem::path& png) {
  RunScore score;
  score.resolution_m = map.resolution;
  score.ate = trajectory_errors(recorder.samples(), options.align);
  // The true walls and starts in the map frame: through the alignment's inverse when aligned.
  const Pose map_from_world = score.ate.alignment.inverse();
  const std::vector<sim::Segment> walls = moved(world_walls, map_from_world);
  const std::vector<Vec2> starts = transformed(map_from_world, recorder.true_starts());
  auto walls_score = score_walls(map, walls);
  if (!walls_score) return walls_score.error();
  score.walls = *walls_score;
  auto coverage = reachable_coverage(map, walls, starts);
  if (!coverage) return coverage.error();
  score.coverage = *coverage;

  std::vector<LineLayer> layers;
  for (const auto& [id, track] : recorder.true_tracks())
    layers.push_back({polyline(track, map_from_world), {80, 160, 255}});
  layers.push_back({walls, {230, 30, 30}});
  SLAM_TRY(viewer::write_png(png.string(), render_overlay(map, layers, options.pixels_per_cell)));

  score.closures =
      audit_corrections(recorder.correction_changes(), score.ate.alignment, options.false_closure_increase_m);
  return score;
}

nlohmann::json to_json(const ErrorStats& s) {
  return {{"count", s.count}, {"mean_m", s.mean}, {"rmse_m", s.rmse}, {"max_m", s.max}};
}

void add_to_json(const RunScore& score, const RunRecorder& recorder, const ScoreOptions& options,
                 nlohmann::json& out) {
  const Pose& a = score.ate.alignment;
  out["aligned"] = options.align;
  out["alignment"] = {{"x", a.x}, {"y", a.y}, {"theta", a.theta}};
  out["ate_corrected"] = to_json(score.ate.corrected);
  out["ate_raw"] = to_json(score.ate.raw);
  out["map"] = {{"resolution_m", score.resolution_m},
                {"occupied_cells", score.walls.occupied_cells},
                {"near_wall_share", score.walls.near_wall_share},
                {"mean_wall_distance_m", score.walls.mean_wall_distance_m},
                {"wall_found_share", score.walls.wall_found_share},
                {"reachable_cells", score.coverage.reachable_cells},
                {"coverage", score.coverage.share()}};
  const ClosureAudit& c = score.closures;
  nlohmann::json false_list = nlohmann::json::array();
  for (const FalseClosure& f : c.false_closure_list)
    false_list.push_back({{"robot", f.robot_id},
                          {"version", f.version},
                          {"truth_stamp_s", static_cast<double>(f.truth_stamp_ns) * 1e-9},
                          {"error_before_m", f.errors.before_m},
                          {"error_after_m", f.errors.after_m}});
  out["closures"] = {{"loop_corrections", c.loop_corrections},
                     {"false_closures", c.false_closures},
                     {"false_closure_increase_m", options.false_closure_increase_m},
                     {"worst_increase_m",
                      c.worst_increase_m ? nlohmann::json(*c.worst_increase_m) : nlohmann::json(nullptr)},
                     {"false_matches", c.false_matches},
                     {"largest_loop_jump_m", c.largest_loop_jump_m},
                     {"largest_jump_m", c.largest_jump_m},
                     {"corrections_scored", c.corrections},
                     {"corrections_unscored", recorder.unscored_corrections()},
                     {"versions_missed", c.versions_missed},
                     {"false", false_list}};
}

}  // namespace slam::bench
