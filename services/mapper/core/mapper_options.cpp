// CLI11 binding and validation of MapperOptions.
#include "mapper/core/mapper_options.hpp"

#include <cmath>

#include "mapper/core/trajectory_export.hpp"

namespace slam::mapper {

void add_mapper_options(CLI::App& app, MapperOptions& o) {
  add_service_options(app, o.service);
  app.footer(
      "Offline commands (no DDS; the store must not be in use by a running mapper):\n"
      "  slam-mapper --store map.db --export map.yaml   rebuild the map from the store, write map.yaml + "
      "map.pgm\n"
      "  slam-mapper --store map.db --import map.yaml   store a ROS map_server map as the prior (applied\n"
      "                                                 under every observation at the next start/rebuild)\n"
      "  slam-mapper --store map.db --export-trajectory sim-1 --trajectory-out sim-1.tum\n"
      "                                                 write a robot's corrected trajectory (TUM or "
      "CARMEN)");

  app.add_option("--store", o.store, "SQLite file of every observation (created with its directory)")
      ->capture_default_str();
  app.add_option("--store-batch", o.store_batch, "observations per store transaction")->capture_default_str();

  GridConfig& g = o.grid;
  app.add_option("--grid-resolution", g.resolution, "metres per cell (a new store's layout)")
      ->capture_default_str();
  app.add_option("--grid-origin-x", g.origin_x, "x of the lower-left corner (m)")->capture_default_str();
  app.add_option("--grid-origin-y", g.origin_y, "y of the lower-left corner (m)")->capture_default_str();
  app.add_option("--grid-width-m", g.width_m, "initial width (m); the grid grows as robots explore")
      ->capture_default_str();
  app.add_option("--grid-height-m", g.height_m, "initial height (m)")->capture_default_str();
  app.add_option("--grid-inflation-radius", g.inflation_radius, "robot radius (m) of the restricted layer")
      ->capture_default_str();
  app.add_flag("--grid-legacy-mode", g.legacy_mode,
               "2019 behaviour: points obstruct their cell, nothing is cleared");
  app.add_option("--grid-max-extent-m", g.max_extent_m, "the grid never grows past this many metres per side")
      ->capture_default_str();
  app.add_option("--grid-grow-chunk-m", g.grow_chunk_m, "growth step (m)")->capture_default_str();
  app.add_option("--grid-max-range-m", g.max_range_m, "a point farther than this from its robot is rejected")
      ->capture_default_str();

  app.add_option("--robot-filter-radius-m", o.robot_filter.radius_m,
                 "a hit this close to another robot's reported position is not an obstacle (0: off)")
      ->capture_default_str();
  app.add_option("--robot-filter-max-age-s", o.robot_filter.max_age_s,
                 "a robot position older than this no longer filters hits")
      ->capture_default_str();

  CompactionOptions& c = o.compaction;
  app.add_option(
         "--store-retention-days", c.retention_days,
         "raw observations older than this are compacted into the per-tile baseline (0: never by age)")
      ->capture_default_str();
  app.add_option(
         "--store-max-mb", c.max_mb,
         "a store using more than this compacts everything older than --store-min-age-s (0: no bound)")
      ->capture_default_str();
  app.add_option("--store-min-age-s", c.min_age_s,
                 "a keyframe first seen or moved less than this long ago (gateway stamps) is never compacted")
      ->capture_default_str();
  app.add_option("--store-compact-interval-s", c.interval_s, "how often the mapper checks whether to compact")
      ->capture_default_str();
  app.add_option("--rerender-min-shift-cells", o.rerender.min_shift_cells,
                 "a keyframe whose points moved less than this many cells is not redrawn")
      ->capture_default_str();
  app.add_option("--rerender-max-tile-fraction", o.rerender.max_tile_fraction,
                 "a re-render redrawing more than this share of the tiles rebuilds the whole grid")
      ->capture_default_str();
  app.add_option("--patch-rate", o.patch_rate_hz, "GridPatch rate (Hz)")->capture_default_str();
  app.add_option("--snapshot-period", o.snapshot_period_s, "full GridSnapshot at least every S seconds")
      ->capture_default_str();
  app.add_option("--max-queued-observations", o.max_queued_observations,
                 "observations waiting for the map loop beyond this are dropped (counted)")
      ->capture_default_str();

  app.add_option("--slam", o.slam, "pose correction: on (correct odometry against the map) or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--slam-old-age-s", o.slam_old_age_s,
                 "a robot's own keyframes this old are matched as the old map (loop closure)")
      ->capture_default_str();
  app.add_option("--slam-global-localisation", o.slam_global_localisation,
                 "a robot that joins a map others have built is searched for on the whole map (every place "
                 "and heading) and drawn only once found; not found within 30 s: placed by its odometry")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option(
         "--slam-lost-robots", o.slam_lost_robots,
         "a placed robot whose keyframes stop fitting the map (carried, odometry broken) is marked lost "
         "(alert), drawn no more and searched for on the whole map until found")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--slam-wall-heading", o.slam_wall_heading,
                 "hold each keyframe's heading to the walls' directions once the map's walls agree on two "
                 "perpendicular ones (off: a building whose walls are square only in places)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();

  app.add_option("--slam-odometry-calibration", o.slam_odometry_calibration,
                 "learn each robot's systematic odometry heading error (drift per metre, turn scale) from "
                 "its matches and take it out of its odometry (off: odometry calibrated already)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();

  app.add_option(
         "--slam-relocalise", o.slam_relocalise,
         "search a sparse robot whose pose has grown loose (a long loop) by its last 4 m of keyframes "
         "among the old keyframes within 3 sigma, closed once three keyframes agree")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();

  app.add_option("--slam-point-refine", o.slam_point_refine,
                 "refine each match against the points of the keyframes around it, not only the grid's "
                 "cells (off: the grid alone, walls up to half a cell off)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();

  app.add_flag("--localise-only", o.localise_only,
               "keep the map as loaded (the store's, or one imported with --import): every robot is searched "
               "for on it and tracked against it, nothing they see is drawn or stored");

  auto* export_flag = app.add_option("--export", o.export_yaml,
                                     "offline: write the stored map to FILE.yaml (+ .pgm) and exit");
  auto* import_flag =
      app.add_option("--import", o.import_yaml, "offline: store FILE.yaml (+ its PGM) as the prior and exit");
  auto* trajectory_flag =
      app.add_option("--export-trajectory", o.export_trajectory,
                     "offline: write ROBOT's stored trajectory to --trajectory-out and exit");
  app.add_option("--trajectory-out", o.trajectory_out, "the trajectory file --export-trajectory writes");
  app.add_option("--trajectory-format", o.trajectory_format,
                 "tum (stamp x y z qx qy qz qw) or carmen (ODOM lines)")
      ->check(CLI::IsMember({"tum", "carmen"}))
      ->capture_default_str();
  export_flag->excludes(import_flag);
  trajectory_flag->excludes(export_flag)->excludes(import_flag);
}

Status validate(const MapperOptions& o) {
  if (o.store.empty()) return Error{"store: must name a file"};
  if (o.store_batch < 1 || o.store_batch > 100000) return Error{"store_batch: must be between 1 and 100000"};
  if (auto s = validate(o.grid); !s) return Error{"grid." + s.message()};
  if (auto s = validate(o.robot_filter); !s) return s;
  if (auto s = validate(o.rerender); !s) return s;
  if (auto s = validate(o.compaction); !s) return s;
  if (!std::isfinite(o.patch_rate_hz) || o.patch_rate_hz < 0.1 || o.patch_rate_hz > 1000.0)
    return Error{"patch_rate: must be between 0.1 and 1000 Hz"};
  if (!std::isfinite(o.snapshot_period_s) || o.snapshot_period_s < 0.1 || o.snapshot_period_s > 3600.0)
    return Error{"snapshot_period: must be between 0.1 and 3600 s"};
  if (o.slam != "on" && o.slam != "off") return Error{"slam: must be on or off"};
  if (o.localise_only && o.slam != "on")
    return Error{"localise_only: needs --slam on (the pose correction places and tracks the robots)"};
  if (!std::isfinite(o.slam_old_age_s) || o.slam_old_age_s < 1.0 || o.slam_old_age_s > 86400.0)
    return Error{"slam_old_age_s: must be between 1 and 86400 s"};
  if (o.max_queued_observations < 1) return Error{"max_queued_observations: must be at least 1"};
  if (!trajectory_format_named(o.trajectory_format)) return Error{"trajectory_format: must be tum or carmen"};
  if (!o.export_trajectory.empty() && o.trajectory_out.empty())
    return Error{"trajectory_out: --export-trajectory needs the file to write"};
  return Status::ok();
}

}  // namespace slam::mapper
