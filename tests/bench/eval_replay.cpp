// eval_replay: runs the mapper's map loop with pose correction on a run eval_mapping recorded
// (<run>.db: the mapper's store, every raw observation in arrival order; <run>.truth: the sampled
// ground truth), deterministically (eval/replay.hpp), and scores it as eval_mapping does. Two builds
// of the pose correction so compare on exactly the same robot paths and drift, in seconds, where two
// live runs differ in both (docs/mapping-quality.md, "Replaying a recorded run"). The robots do not
// react to the replayed map (their paths are the recorded ones): a live run stays the final word.
// Writes <out>/<name>.json, <name>.png and the exported <name>.yaml/.pgm; prints one summary line.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "eval/replay.hpp"
#include "eval/run_score.hpp"
#include "eval/truth_log.hpp"
#include "simulator/core/builtin_worlds.hpp"

namespace slam::bench {
namespace {

struct Options {
  std::string run;  // path prefix of the recording: <run>.db and <run>.truth
  std::string world;
  std::string out_dir = "build/bench/replay";
  std::string name;  // default: the recording's file name
  std::string log_level = "warn";
  std::string wall_heading = "on";
  std::string point_refine = "on";
  std::string odometry_calibration = "on";
  ReplayOptions replay;
  ScoreOptions score;

  std::string run_name() const {
    return name.empty() ? std::filesystem::path(run).filename().string() : name;
  }
};

Result<nlohmann::json> run(const Options& o) {
  auto world = sim::builtin_world(o.world);
  if (!world) return world.error();
  auto observations = read_observations(o.run + ".db");
  if (!observations) return observations.error();
  auto truth = read_truth_log(o.run + ".truth");
  if (!truth) return truth.error();
  std::filesystem::create_directories(o.out_dir);
  const std::string base = std::filesystem::absolute(o.out_dir + "/" + o.run_name()).string();
  RunRecorder recorder(0, 0.2);  // every truth sample of the recording is a sample
  auto outcome = replay(*observations, *truth, o.replay, recorder, base + ".yaml");
  if (!outcome) return outcome.error();
  auto image = read_ros_map(base + ".yaml");
  if (!image) return Error{"reading the exported map: " + image.message()};
  auto score = score_run(recorder, *image, world->walls(), o.score, base + ".png");
  if (!score) return score.error();

  nlohmann::json j;
  j["name"] = o.run_name();
  j["recording"] = o.run;
  j["world"] = o.world;
  j["phase_ms"] = o.replay.phase_ms;
  j["wall_heading"] = o.wall_heading;
  j["point_refine"] = o.point_refine;
  j["odometry_calibration"] = o.odometry_calibration;
  j["observations"] = observations->size();
  j["recorded_s"] = outcome->recorded_s;
  j["wall_s"] = outcome->wall_s;
  add_to_json(*score, recorder, o.score, j);
  const correction::CorrectorStats& st = outcome->stats;
  j["slam"] = {{"keyframes", st.keyframes},
               {"matched", st.matched},
               {"unmatched", st.unmatched},
               {"robots_lost", st.robots_lost},
               {"standing", st.standing},
               {"closures_tried", st.closures_tried},
               {"closures_accepted", st.closures_accepted},
               {"closures_rejected", st.closures_rejected},
               {"wall_headings", st.wall_headings},
               {"point_refined", st.point_refined},
               {"optimisations", st.optimisations}};
  j["image"] = std::filesystem::path(base + ".png").filename().string();
  return j;
}

}  // namespace
}  // namespace slam::bench

int main(int argc, char** argv) {
  slam::bench::Options o;
  CLI::App app{"eval_replay: the pose correction run offline on a recorded eval_mapping run, scored"};
  app.add_option("run", o.run, "the recording's path without extension (<run>.db and <run>.truth)")
      ->required();
  app.add_option("--world", o.world, "the built-in world the run was recorded in")->required();
  app.add_option("--out", o.out_dir, "directory of the results")->capture_default_str();
  app.add_option("--name", o.name, "result file names (default: the recording's name)");
  app.add_option("--log-level", o.log_level, "log level of the pose correction (info lists loop closures)")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}))
      ->capture_default_str();
  app.add_option("--phase-ms", o.replay.phase_ms,
                 "offset of the loop's passes (ms): the same run with another timing of the map loop")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  app.add_flag("--trace", o.replay.trace,
               "log each robot's corrected-pose error at every truth instant (info)");
  app.add_flag("--trace-keyframes", o.replay.trace_keyframes,
               "log each keyframe's predicted, matched and placed pose against the truth (info)");
  app.add_option("--wall-heading", o.wall_heading, "the mapper's --slam-wall-heading: on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--point-refine", o.point_refine, "the mapper's --slam-point-refine: on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--odometry-calibration", o.odometry_calibration,
                 "the mapper's --slam-odometry-calibration: on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_flag("--align", o.score.align, "fit the map frame to the world first (--odom-frame start runs)");
  app.add_option("--false-closure-increase", o.score.false_closure_increase_m,
                 "error increase (m) beyond which a loop-closure correction counts as false")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(o.log_level));
  o.replay.wall_heading = o.wall_heading == "on";
  o.replay.point_refine = o.point_refine == "on";
  o.replay.odometry_calibration = o.odometry_calibration == "on";

  auto result = slam::bench::run(o);
  if (!result) {
    std::fprintf(stderr, "eval_replay: %s: %s\n", o.run_name().c_str(), result.message().c_str());
    return 1;
  }
  const std::string json_path = o.out_dir + "/" + o.run_name() + ".json";
  std::ofstream(json_path) << result->dump(2) << "\n";
  const auto& j = *result;
  std::printf(
      "%s: ATE %.1f / %.1f cm (raw %.1f / %.1f), near a wall %.1f %%, walls found %.1f %%, mean %.1f cm, "
      "loop corrections %d, false %d, worst %+.1f cm (%.0f s)\n",
      o.run_name().c_str(), 100 * j["ate_corrected"]["rmse_m"].get<double>(),
      100 * j["ate_corrected"]["max_m"].get<double>(), 100 * j["ate_raw"]["rmse_m"].get<double>(),
      100 * j["ate_raw"]["max_m"].get<double>(), 100 * j["map"]["near_wall_share"].get<double>(),
      100 * j["map"]["wall_found_share"].get<double>(), 100 * j["map"]["mean_wall_distance_m"].get<double>(),
      j["closures"]["loop_corrections"].get<int>(), j["closures"]["false_closures"].get<int>(),
      j["closures"]["worst_increase_m"].is_null() ? 0.0
                                                  : 100 * j["closures"]["worst_increase_m"].get<double>(),
      j["wall_s"].get<double>());
  return 0;
}
