#pragma once
// slam-mapper's configuration: the store, the grid defaults (the core's GridConfig), the publishing
// rates and the offline commands (--export, --import, --export-trajectory), with defaults, CLI11/YAML
// binding and one validator. Flags are named after the keys: `grid.resolution` is --grid-resolution
// on the command line and `grid: {resolution: 0.05}` in a --config file.
#include <CLI/CLI.hpp>
#include <string>

#include "common/core/result.hpp"
#include "common/core/service_options.hpp"
#include "mapper/core/compaction_options.hpp"
#include "mapper/core/grid_config.hpp"
#include "mapper/core/rerender_options.hpp"
#include "mapper/core/robot_footprints.hpp"

namespace slam::mapper {

struct MapperOptions {
  ServiceOptions service;
  // SQLite file holding every observation; its directory is created when missing.
  std::string store = "run/data/map.db";
  int store_batch = 512;         // appends per transaction (a commit also happens every patch period)
  CompactionOptions compaction;  // how long raw observations are kept, how large the store may grow
  // The layout of a new store. A store remembers the layout GridConfig requests set last; that layout
  // (resolution, origin, size, inflation, legacy mode) wins over these flags at start.
  GridConfig grid;
  FootprintConfig robot_filter;             // hits on other robots become misses
  RerenderOptions rerender;                 // what a re-render after moved keyframes redraws
  double patch_rate_hz = 10.0;              // GridPatch rate (the changed box since the last patch)
  double snapshot_period_s = 5.0;           // a full GridSnapshot at least this often
  size_t max_queued_observations = 100000;  // intake bound: beyond it observations are dropped, counted
  // Pose correction (SLAM): "on" corrects every robot's odometry against the map, "off" trusts the
  // reported poses (odometry frame = map frame).
  std::string slam = "on";
  double slam_old_age_s = 60.0;                  // own keyframes this old count as the old map (loop closure)
  std::string slam_global_localisation = "off";  // a robot joining a mapped building is searched for on it
  std::string slam_lost_robots = "on";   // a robot whose scans stop fitting the map is searched for again
  std::string slam_wall_heading = "on";  // keyframe headings held to the walls' directions
  std::string slam_point_refine = "on";  // matches refined against the keyframes' own points
  std::string slam_odometry_calibration = "on";  // each robot's systematic odometry heading error taken out
  std::string slam_relocalise = "on";  // a loose sparse robot searched for by its trail among old keyframes
  // The map stays as loaded (a building mapped once): robots are searched for on it and tracked
  // against it; nothing they see is drawn or stored.
  bool localise_only = false;
  // Offline commands (no DDS): rebuild from the store and write a ROS map, store a map as prior, or
  // write one robot's trajectory (to trajectory_out, as tum or carmen).
  std::string export_yaml;
  std::string import_yaml;
  std::string export_trajectory;  // the robot
  std::string trajectory_out;
  std::string trajectory_format = "tum";

  bool slam_enabled() const { return slam == "on"; }
  bool offline() const { return !export_yaml.empty() || !import_yaml.empty() || !export_trajectory.empty(); }
};

// Adds the common flags and every mapper flag to `app`, bound to `options`.
void add_mapper_options(CLI::App& app, MapperOptions& options);

// Ok, or the first bad key with the reason.
Status validate(const MapperOptions& options);

}  // namespace slam::mapper
