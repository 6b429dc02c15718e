// eval_replay: runs the mapper's map loop with pose correction (Mapper + CorrectionStage, no DDS,
// no other process) on a run eval_mapping recorded (<run>.db: the mapper's store, every raw
// observation in arrival order; <run>.truth: the sampled ground truth) and scores it as eval_mapping
// does. The loop steps every 100 ms of the observations' own clock, as the mapper's does, but
// deterministically: keyframes are matched inline and every optimisation and re-render is waited for.
// So two builds of the pose correction compare on exactly the same robot paths and drift, in about
// a minute, where two live runs differ in both (docs/mapping-quality.md, "Replaying a run").
// The robots do not react to the replayed map (their paths are the recorded ones): a live
// eval_mapping run stays the final word.
// Writes <out>/<name>.json, <name>.png and the exported <name>.yaml/.pgm; prints one summary line.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "eval/run_recorder.hpp"
#include "eval/run_score.hpp"
#include "eval/truth_log.hpp"
#include "mapper/correction_stage.hpp"
#include "mapper/map_files.hpp"
#include "mapper/mapper.hpp"
#include "mapper/observation_store.hpp"
#include "simulator/builtin_worlds.hpp"
#include "temp_dir.hpp"

namespace slam::bench {
namespace {

constexpr int64_t kLoopPeriodNs = 100'000'000;  // the mapper's patch period: one loop pass

struct ReplayOptions {
  std::string run;  // path prefix of the recording: <run>.db and <run>.truth
  std::string world;
  std::string out_dir = "build/bench/replay";
  std::string name;  // default: the recording's file name
  std::string log_level = "warn";
  double phase_ms = 0.0;  // the loop's first pass this long after the first observation (+ one period)
  bool trace = false;     // log every robot's corrected-pose error at every truth instant
  ScoreOptions score;
};

Result<std::vector<mapper::OwnedObservation>> read_observations(const std::filesystem::path& db) {
  if (!std::filesystem::exists(db)) return Error{"no recording " + db.string()};
  auto store = mapper::ObservationStore::open(db);
  if (!store) return store.error();
  std::vector<mapper::OwnedObservation> out;
  SLAM_TRY(store->for_each([&](const mapper::ObservationRecord& r) {
    out.emplace_back().assign(r.robot_id, r.seq, r.stamp_ns, r.obs);
  }));
  if (out.empty()) return Error{db.string() + " holds no observation"};
  return out;
}

class Replay {
 public:
  explicit Replay(const ReplayOptions& o) : o_(o), recorder_(0, 0.2) {}

  std::string name() const {
    return o_.name.empty() ? std::filesystem::path(o_.run).filename().string() : o_.name;
  }

  Result<nlohmann::json> run() {
    auto world = sim::builtin_world(o_.world);
    if (!world) return world.error();
    auto observations = read_observations(o_.run + ".db");
    if (!observations) return observations.error();
    auto truth = read_truth_log(o_.run + ".truth");
    if (!truth) return truth.error();

    testkit::TempDir dir("eval-replay");
    mapper::MapperOptions options;
    options.store = (dir.path() / "map.db").string();
    Counters counters;
    auto made = mapper::Mapper::create(options, counters, 1, [] {});
    if (!made) return made.error();
    mapper::Mapper& map = **made;
    correction::CorrectorOptions slam_options;
    slam_options.old_age_s = options.slam_old_age_s;
    slam_options.match_threads = 0;  // inline: deterministic
    mapper::CorrectionStage stage(true, slam_options);

    recorder_.start();
    const auto wall0 = std::chrono::steady_clock::now();
    const int64_t t0 = observations->front().stamp_ns;
    size_t next_obs = 0, next_truth = 0;
    std::vector<correction::RobotCorrection> changed;
    std::vector<RobotTruth> instant;
    std::map<std::string, Pose> corrections;  // each robot's latest, for the trace
    for (int64_t tick = t0 + kLoopPeriodNs + static_cast<int64_t>(o_.phase_ms * 1e6);
         next_obs < observations->size() || next_truth < truth->size(); tick += kLoopPeriodNs) {
      const int64_t mono = tick - t0;
      map.poll_rebuild();
      for (; next_obs < observations->size() && (*observations)[next_obs].stamp_ns <= tick; ++next_obs) {
        const mapper::OwnedObservation& r = (*observations)[next_obs];
        stage.add(map, mapper::RobotScan{r.robot_id, r.seq, r.stamp_ns, r.view(), 0, Pose{}}, mono);
      }
      stage.step(map, tick, mono);
      // Optimisations and re-renders land within this pass, whatever their time.
      map.wait_for_rebuild();
      while (stage.optimising()) {
        stage.wait_for_optimisation();
        stage.step(map, tick, mono);
        map.wait_for_rebuild();
      }
      map.commit();
      changed.clear();
      stage.take_changed(changed);
      for (const auto& c : changed) {
        recorder_.on_correction(c.robot, c.map_from_odom, c.version,
                                c.source == correction::CorrectionSource::Loop);
        corrections[c.robot] = c.map_from_odom;
      }
      while (next_truth < truth->size() && (*truth)[next_truth].stamp_ns <= tick) {
        const int64_t stamp = (*truth)[next_truth].stamp_ns;
        instant.clear();
        for (; next_truth < truth->size() && (*truth)[next_truth].stamp_ns == stamp; ++next_truth)
          instant.push_back((*truth)[next_truth].truth);
        recorder_.on_truth(stamp, instant);
        for (const RobotTruth& t : instant) {
          if (!o_.trace) break;
          const Vec2 corrected = corrections[t.robot_id].compose(t.reported_pose).position();
          spdlog::info("trace {:.1f} s {} error {:.3f} m, raw {:.3f} m",
                       static_cast<double>(stamp - t0) * 1e-9, t.robot_id,
                       distance(corrected, t.true_pose.position()),
                       distance(t.reported_pose.position(), t.true_pose.position()));
        }
      }
    }
    recorder_.stop();
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

    std::filesystem::create_directories(o_.out_dir);
    const std::string base = std::filesystem::absolute(o_.out_dir + "/" + name()).string();
    const mapper::FileOutcome exported = mapper::export_map_file(map.grid(), base + ".yaml");
    if (!exported.ok()) return Error{"map export: " + exported.message};
    auto image = read_ros_map(base + ".yaml");
    if (!image) return Error{"reading the exported map: " + image.message()};
    auto score = score_run(recorder_, *image, world->walls(), o_.score, base + ".png");
    if (!score) return score.error();

    nlohmann::json j;
    j["name"] = name();
    j["recording"] = o_.run;
    j["world"] = o_.world;
    j["observations"] = observations->size();
    j["recorded_s"] = static_cast<double>(observations->back().stamp_ns - t0) * 1e-9;
    j["wall_s"] = wall_s;
    add_to_json(*score, recorder_, o_.score, j);
    const correction::CorrectorStats& st = stage.stats();
    j["slam"] = {{"keyframes", st.keyframes},
                 {"matched", st.matched},
                 {"unmatched", st.unmatched},
                 {"closures_tried", st.closures_tried},
                 {"closures_accepted", st.closures_accepted},
                 {"closures_rejected", st.closures_rejected},
                 {"optimisations", st.optimisations}};
    j["image"] = std::filesystem::path(base + ".png").filename().string();
    return j;
  }

 private:
  ReplayOptions o_;
  RunRecorder recorder_;
};

}  // namespace
}  // namespace slam::bench

int main(int argc, char** argv) {
  slam::bench::ReplayOptions o;
  CLI::App app{"eval_replay: the pose correction run offline on a recorded eval_mapping run, scored"};
  app.add_option("run", o.run, "the recording's path without extension (<run>.db and <run>.truth)")
      ->required();
  app.add_option("--world", o.world, "the built-in world the run was recorded in")->required();
  app.add_option("--out", o.out_dir, "directory of the results")->capture_default_str();
  app.add_option("--name", o.name, "result file names (default: the recording's name)");
  app.add_option("--log-level", o.log_level, "log level of the pose correction (info lists loop closures)")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}))
      ->capture_default_str();
  app.add_option("--phase-ms", o.phase_ms,
                 "offset of the loop's passes (ms): the same run with another timing of the map loop")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  app.add_flag("--trace", o.trace, "log each robot's corrected-pose error at every truth instant (info)");
  app.add_flag("--align", o.score.align, "fit the map frame to the world first (--odom-frame start runs)");
  app.add_option("--false-closure-increase", o.score.false_closure_increase_m,
                 "error increase (m) beyond which a loop-closure correction counts as false")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(o.log_level));

  slam::bench::Replay replay(o);
  auto result = replay.run();
  if (!result) {
    std::fprintf(stderr, "eval_replay: %s: %s\n", replay.name().c_str(), result.message().c_str());
    return 1;
  }
  const std::string json_path = o.out_dir + "/" + replay.name() + ".json";
  std::ofstream(json_path) << result->dump(2) << "\n";
  const auto& j = *result;
  std::printf(
      "%s: ATE %.1f / %.1f cm (raw %.1f / %.1f), near a wall %.1f %%, walls found %.1f %%, mean %.1f cm, "
      "loop corrections %d, false %d, worst %+.1f cm (%.0f s)\n",
      replay.name().c_str(), 100 * j["ate_corrected"]["rmse_m"].get<double>(),
      100 * j["ate_corrected"]["max_m"].get<double>(), 100 * j["ate_raw"]["rmse_m"].get<double>(),
      100 * j["ate_raw"]["max_m"].get<double>(), 100 * j["map"]["near_wall_share"].get<double>(),
      100 * j["map"]["wall_found_share"].get<double>(), 100 * j["map"]["mean_wall_distance_m"].get<double>(),
      j["closures"]["loop_corrections"].get<int>(), j["closures"]["false_closures"].get<int>(),
      j["closures"]["worst_increase_m"].is_null() ? 0.0
                                                  : 100 * j["closures"]["worst_increase_m"].get<double>(),
      j["wall_s"].get<double>());
  return 0;
}
