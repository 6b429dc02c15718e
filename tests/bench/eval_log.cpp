// eval_log: a real robot's log (CARMEN, e.g. the Freiburg SLAM benchmark's) run through the mapper's
// map loop with pose correction, offline and deterministically (eval/replay.hpp), and scored with the
// benchmark's relation metric (eval/relation_metric.hpp): the final optimised trajectory, the poses
// published while driving (each scan placed by the correction in force when it arrived: what the
// gateway hands the planner), and raw odometry. Scans become observations as the gateway decodes them
// (eval/log_observations.hpp). Writes <out>/<name>.json, <name>.png and the exported map; prints one
// summary line.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "common/core/map_io.hpp"
#include "eval/log_observations.hpp"
#include "eval/map_overlay.hpp"
#include "eval/relation_metric.hpp"
#include "eval/replay.hpp"
#include "mapper/core/map_files.hpp"
#include "mapper/core/observation_store.hpp"
#include "mapper/core/trajectory_export.hpp"
#include "simulator/robot_log/carmen_log.hpp"
#include "viewer/core/png_file.hpp"

namespace slam::bench {
namespace {

constexpr int64_t kLoopPeriodNs = 100'000'000;  // the mapper's loop period
constexpr double kShortRelation_s = 10.0;       // "short" relations: within this many seconds

std::string strip_log_extension(std::string p) {
  for (const char* ext : {".gz", ".clf", ".log"})
    if (p.ends_with(ext)) p.resize(p.size() - std::string_view(ext).size());
  return p;
}

struct Options {
  std::string log;
  std::string relations;  // default: the log's path with .relations for .clf(.gz)
  std::string out_dir = "build/bench/logs";
  std::string name;
  std::string log_level = "warn";
  LogObservationOptions observations;
  correction::CorrectorOptions slam;
  int pieces = 1;  // the log cut into this many robots, each switched on where its piece starts

  std::string run_name() const {
    if (!name.empty()) return name;
    return strip_log_extension(std::filesystem::path(log).filename().string()) +
           (observations.v1 ? "-v1" : "") +
           (observations.beams > 0 ? fmt::format("-{}beams", observations.beams) : "") +
           (pieces > 1 ? fmt::format("-{}pieces", pieces) : "");
  }
  std::string relation_path() const {
    return relations.empty() ? strip_log_extension(log) + ".relations" : relations;
  }
};

nlohmann::json to_json(const RelationScore& s) {
  auto ms = [](const MeanStd& m) { return nlohmann::json{{"mean", m.mean}, {"std", m.std}}; };
  return {{"relations", s.relations},      {"missing", s.missing},         {"trans_abs_m", ms(s.trans_abs)},
          {"trans_sq_m2", ms(s.trans_sq)}, {"rot_abs_deg", ms(s.rot_abs)}, {"rot_sq_deg2", ms(s.rot_sq)}};
}

// Robot poses from sensor poses (the observations carry the sensor's).
std::vector<Pose> robot_poses(std::span<const Pose> sensor, std::span<const Pose> sensor_in_robot) {
  std::vector<Pose> out(sensor.size());
  for (size_t i = 0; i < sensor.size(); ++i) out[i] = sensor[i].compose(sensor_in_robot[i].inverse());
  return out;
}

// Each scan placed by its keyframe's correction as the store holds it now (the final trajectory). The
// log's own odometry pose is used, so a v1 run (no heading sent) is scored on its heading too.
Result<std::vector<Pose>> final_sensor_poses(DeterministicMapLoop& loop, const LogObservations& log) {
  loop.map().commit();
  auto store = mapper::ObservationStore::open(loop.store_path());
  if (!store) return store.error();
  auto keyframes = store->keyframes();
  if (!keyframes) return keyframes.error();
  std::unordered_map<mapper::KeyframeId, Pose> corrections;
  for (const mapper::Keyframe& k : *keyframes) corrections[k.id] = k.map_from_odom;
  std::vector<Pose> out(log.sensor_odom.size());
  SLAM_TRY(store->for_each([&](const mapper::ObservationRecord& r) {
    if (r.seq == 0 || r.seq > out.size()) return;
    const auto it = corrections.find(r.keyframe_id);
    out[r.seq - 1] = (it == corrections.end() ? Pose{} : it->second).compose(log.sensor_odom[r.seq - 1]);
  }));
  return out;
}

// The log cut into `pieces` robots one after another, each as if switched on where its piece starts:
// its odometry from (0, 0, 0), its own robot id. Relations between stamps of different pieces then
// measure how well the robots were placed on each other's map.
LogObservations piece_observations(std::vector<robot_log::LaserScan> scans, int pieces,
                                   LogObservationOptions options) {
  if (pieces <= 1) return log_observations(scans, options);
  LogObservations out;
  const size_t n = scans.size();
  for (size_t k = 0; k < static_cast<size_t>(pieces); ++k) {
    const size_t from = n * k / static_cast<size_t>(pieces), to = n * (k + 1) / static_cast<size_t>(pieces);
    const Pose origin = scans[from].odom.inverse();
    for (size_t i = from; i < to; ++i) scans[i].odom = origin.compose(scans[i].odom);
    options.robot = fmt::format("piece-{}", k + 1);
    LogObservations piece = log_observations(std::span(scans).subspan(from, to - from), options);
    for (mapper::OwnedObservation& obs : piece.observations) obs.seq += from;
    std::move(piece.observations.begin(), piece.observations.end(), std::back_inserter(out.observations));
    out.stamps_s.insert(out.stamps_s.end(), piece.stamps_s.begin(), piece.stamps_s.end());
    out.sensor_odom.insert(out.sensor_odom.end(), piece.sensor_odom.begin(), piece.sensor_odom.end());
    out.sensor_in_robot.insert(out.sensor_in_robot.end(), piece.sensor_in_robot.begin(),
                               piece.sensor_in_robot.end());
  }
  return out;
}

struct Played {
  std::vector<Pose> published;  // sensor poses, by the correction in force at each scan's arrival
  std::vector<Pose> final;      // sensor poses, by the final trajectory
  correction::CorrectorStats stats;
  double wall_s = 0.0;
};

Result<Played> play(const LogObservations& log, const correction::CorrectorOptions& slam,
                    const std::filesystem::path& yaml_path) {
  auto made = DeterministicMapLoop::create(slam);
  if (!made) return made.error();
  DeterministicMapLoop& loop = **made;
  Played played;
  played.published.resize(log.observations.size());
  const auto wall0 = std::chrono::steady_clock::now();
  const int64_t t0 = log.observations.front().stamp_ns;
  std::unordered_map<std::string, Pose> corrections;  // per robot (a piece of the log)
  std::vector<correction::RobotCorrection> changed;
  size_t next = 0;
  int64_t tick = t0 + kLoopPeriodNs;
  for (; next < log.observations.size(); tick += kLoopPeriodNs) {
    for (; next < log.observations.size() && log.observations[next].stamp_ns <= tick; ++next) {
      loop.add(log.observations[next], tick - t0);
      played.published[next] = corrections[log.observations[next].robot_id].compose(log.sensor_odom[next]);
    }
    changed.clear();
    loop.step(tick, tick - t0, changed);
    for (const auto& c : changed) corrections[c.robot] = c.map_from_odom;
  }
  changed.clear();
  loop.finish(tick, tick - t0, changed);
  auto final = final_sensor_poses(loop, log);
  if (!final) return final.error();
  played.final = std::move(*final);
  played.stats = loop.stage().stats();
  played.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const mapper::FileOutcome exported = mapper::export_map_file(loop.map().grid(), yaml_path.string());
  if (!exported.ok()) return Error{"map export: " + exported.message};
  return played;
}

Result<nlohmann::json> run(const Options& o) {
  auto read = robot_log::read_carmen_log(o.log);
  if (!read) return read.error();
  if (read->scans.empty()) return Error{o.log + " holds no scan"};
  auto relations = read_relations(o.relation_path());
  if (!relations) return relations.error();
  if (o.pieces > 1 && read->scans.size() < static_cast<size_t>(o.pieces))
    return Error{"fewer scans than --pieces"};
  const LogObservations log = piece_observations(read->scans, o.pieces, o.observations);
  std::filesystem::create_directories(o.out_dir);
  const std::string base = std::filesystem::absolute(o.out_dir + "/" + o.run_name()).string();
  auto played = play(log, o.slam, base + ".yaml");
  if (!played) return played.error();

  auto image = read_ros_map(base + ".yaml");
  if (!image) return Error{"reading the exported map: " + image.message()};
  SLAM_TRY(viewer::write_png(base + ".png", render_overlay(*image, {}, 1)));

  nlohmann::json j;
  j["name"] = o.run_name();
  j["log"] = o.log;
  j["scans"] = log.observations.size();
  j["bad_lines"] = read->stats.bad_lines;
  j["stamps_back"] = read->stats.stamps_back;
  j["beams"] = o.observations.beams;
  j["max_range_m"] = o.observations.max_range_m;
  j["protocol"] = o.observations.v1 ? "v1" : "v2";
  j["log_s"] = log.stamps_s.back() - log.stamps_s.front();
  j["wall_s"] = played->wall_s;
  const std::pair<const char*, const std::vector<Pose>*> estimates[] = {
      {"final", &played->final}, {"published", &played->published}, {"odometry", &log.sensor_odom}};
  for (const auto& [key, sensor] : estimates) {
    const StampedPoses poses(log.stamps_s, robot_poses(*sensor, log.sensor_in_robot));
    j[key]["all"] = to_json(score_relations(*relations, poses));
    j[key]["short"] = to_json(score_relations(*relations, poses, 0.0, kShortRelation_s));
  }
  // The final trajectory as TUM text, the robot's stamps (what `slamctl trajectory` writes live).
  std::vector<mapper::TrajectoryPose> tum;
  const std::vector<Pose> final_robot = robot_poses(played->final, log.sensor_in_robot);
  for (size_t i = 0; i < final_robot.size(); ++i)
    tum.push_back({static_cast<int64_t>(std::llround(log.stamps_s[i] * 1e9)), final_robot[i], true});
  SLAM_TRY(mapper::write_trajectory(tum, base + ".tum", mapper::TrajectoryFormat::Tum));
  const correction::CorrectorStats& st = played->stats;
  j["slam"] = {{"keyframes", st.keyframes},
               {"matched", st.matched},
               {"unmatched", st.unmatched},
               {"robots_lost", st.robots_lost},
               {"closures_tried", st.closures_tried},
               {"closures_accepted", st.closures_accepted},
               {"closures_rejected", st.closures_rejected},
               {"optimisations", st.optimisations},
               {"segments", st.segments},
               {"robots_placed", st.robots_placed},
               {"unplaced_keyframes_dropped", st.unplaced_keyframes_dropped}};
  j["pieces"] = o.pieces;
  j["image"] = std::filesystem::path(base + ".png").filename().string();
  return j;
}

// The pose correction's tuning knobs (CorrectorOptions, pose_corrector.hpp), to try a change on the
// logs before it becomes a default; the defaults are the service's.
void add_slam_options(CLI::App& app, correction::CorrectorOptions& s) {
  auto* g = app.add_option_group("pose correction", "CorrectorOptions fields (defaults: the mapper's)");
  auto add = [&](const char* name, auto& value, const char* help) {
    g->add_option(name, value, help)->capture_default_str();
  };
  add("--scan-points", s.keyframe.scan_points,
      "a message with this many points is a laser scan, matchable alone");
  add("--scan-travel", s.keyframe.scan_travel_m, "a keyframe of scans closes after this travel (m)");
  add("--scan-turn", s.keyframe.scan_turn_rad, "...or this turn (rad)");
  add("--keyframe-travel", s.keyframe.travel_m, "a sparse keyframe closes after this travel (m)");
  add("--keyframe-turn", s.keyframe.turn_rad, "...or this turn (rad)");
  add("--keyframe-messages", s.keyframe.max_messages, "...or this many messages");
  add("--scan-track-window-m", s.scan_track_window.linear_m, "tracking search of a scan keyframe (m)");
  add("--scan-track-window-rad", s.scan_track_window.angular_rad, "...and its heading (rad)");
  add("--track-window-m", s.track_window.linear_m, "tracking search of a sparse keyframe (m)");
  add("--track-window-rad", s.track_window.angular_rad, "...and its heading (rad)");
  add("--scan-track-variance-scale", s.scan_track_variance_scale, "a scan match's covariance scale");
  add("--scan-independent-points", s.scan_independent_points, "independent points of a scan keyframe");
  add("--scan-max-ambiguity", s.scan_distinct.max_ambiguity, "a scan closure's largest ambiguity");
  add("--track-variance-scale", s.track_variance_scale, "a sparse match's covariance scale");
  add("--closure-window-m", s.closure_window.linear_m, "loop-closure search (m)");
  add("--closure-window-rad", s.closure_window.angular_rad, "...and its heading (rad)");
  add("--scan-recovery-window-m", s.scan_recovery_window.linear_m,
      "a scan match on its window's edge searched again this wide (m)");
  add("--scan-recovery-window-rad", s.scan_recovery_window.angular_rad, "...and its heading (rad)");
  add("--scan-recovery-gain", s.scan_recovery_gain, "...and taken when it scores this much better");
  add("--closure-radius", s.closure_radius_m, "old keyframes this near are closure candidates (m)");
  add("--relocalise", s.relocalise, "search a loose sparse robot by its trail (true/false)");
  add("--relocalise-sigma", s.relocalise_sigma_m,
      "a sparse robot whose chain is looser than this (m) is searched for by its trail");
  add("--relocalise-max-m", s.relocalise_max_m, "...at most this far (m)");
  add("--relocalise-max-rad", s.relocalise_max_rad, "...and this much turned (rad)");
  add("--local-reach", s.local_reach_m, "the local maps' largest reach (m)");
  add("--odom-sigma-m", s.odom_sigma_m_per_sqrt_m, "odometry noise (m per sqrt m)");
  add("--odom-sigma-rad", s.odom_sigma_rad_per_m, "odometry heading noise (rad per m)");
  add("--wall-heading", s.wall_heading, "hold headings to the walls' axes (true/false)");
  add("--point-refine", s.point_refine, "refine matches against the points (true/false)");
  add("--odometry-calibration", s.odometry_calibration,
      "learn each robot's odometry heading error and take it out (true/false)");
  add("--odometry-direction", s.odometry_direction,
      "turn odometry that counts backward driving as forward round while matches show it (true/false)");
  add("--placement-trail", s.placement_trail_m,
      "travel (m) of keyframes searched together for an unplaced robot");
  add("--placement-max-crossed-walls", s.placement_max_crossed_walls,
      "share of a placement's rays that may cross walls");
  add("--placement-whole-map-cells", s.placement_whole_map_cells,
      "cells of the map searched whole at every heading (coarsened to fit)");
  add("--global-localisation", s.global_localisation,
      "search for each robot joining the map on it before drawing it (true/false)");
}

std::string row(const nlohmann::json& j, const char* key) {
  const auto& a = j[key]["all"];
  const auto& s = j[key]["short"];
  return fmt::format("{:.3f} ± {:.3f} m {:.2f}° (short {:.3f} m)", a["trans_abs_m"]["mean"].get<double>(),
                     a["trans_abs_m"]["std"].get<double>(), a["rot_abs_deg"]["mean"].get<double>(),
                     s["trans_abs_m"]["mean"].get<double>());
}

}  // namespace
}  // namespace slam::bench

int main(int argc, char** argv) {
  slam::bench::Options o;
  CLI::App app{
      "eval_log: a robot's CARMEN log through the pose correction, offline, scored with its relation file"};
  app.add_option("log", o.log, "CARMEN log (.clf or .clf.gz)")->required()->check(CLI::ExistingFile);
  app.add_option("--relations", o.relations, "relation file (default: the log's name with .relations)");
  app.add_option("--out", o.out_dir, "directory of the results")->capture_default_str();
  app.add_option("--name", o.name, "result file names (default: from the log's name)");
  app.add_option("--beams", o.observations.beams, "thin each scan to N evenly spaced beams (0: all)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  app.add_option("--max-range", o.observations.max_range_m, "returns beyond this (m) count as no return")
      ->check(CLI::Range(0.5, 1000.0))
      ->capture_default_str();
  app.add_option("--free-range", o.observations.free_range_m,
                 "a beam without a return clears this far (m), as the gateway's --scan-free-range-m")
      ->check(CLI::Range(0.1, 1000.0))
      ->capture_default_str();
  app.add_flag("--v1", o.observations.v1,
               "as a legacy v1 robot: centimetre positions, no heading, <= 16 points");
  app.add_option("--pieces", o.pieces,
                 "cut the log into N robots, each switched on where its piece starts (odometry from 0, 0, 0)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  app.add_option("--log-level", o.log_level, "log level of the pose correction")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}))
      ->capture_default_str();
  slam::bench::add_slam_options(app, o.slam);
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(o.log_level));

  auto result = slam::bench::run(o);
  if (!result) {
    std::fprintf(stderr, "eval_log: %s: %s\n", o.run_name().c_str(), result.message().c_str());
    return 1;
  }
  std::ofstream(o.out_dir + "/" + o.run_name() + ".json") << result->dump(2) << "\n";
  const auto& j = *result;
  std::printf("%s: final %s | published %s | odometry %s | %d keyframes, %d closures, %.0f s for %.0f s\n",
              o.run_name().c_str(), slam::bench::row(j, "final").c_str(),
              slam::bench::row(j, "published").c_str(), slam::bench::row(j, "odometry").c_str(),
              j["slam"]["keyframes"].get<int>(), j["slam"]["closures_accepted"].get<int>(),
              j["wall_s"].get<double>(), j["log_s"].get<double>());
  return 0;
}
