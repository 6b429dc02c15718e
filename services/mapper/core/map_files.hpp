#pragma once
// What the mapper does with files, shared by the DDS edge (MapFileRequest) and the offline commands
// (--export/--import): opening the store, choosing the start-up layout, and ROS map export/import
// with failures sorted into the kinds a MapReply distinguishes (bad request, I/O, bad file, and for
// trajectories, trajectory_export.hpp, unknown robot).
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "common/core/map_io.hpp"
#include "common/core/result.hpp"
#include "mapper/core/grid_config.hpp"
#include "mapper/core/map_error.hpp"
#include "mapper/core/observation_store.hpp"
#include "mapper/core/occupancy_grid.hpp"

namespace slam::mapper {

// Opens (creating its directory when missing) the store; errors name the path.
Result<ObservationStore> open_store(const std::filesystem::path& path, StoreOptions options = {});

// The layout a request may set (resolution, origin, size, inflation, legacy mode) comes from the
// store when it has one saved; every other field from `defaults`. Errors name the store.
Result<GridConfig> startup_config(const GridConfig& defaults, ObservationStore& store);

// True when the fields a GridConfig request sets are equal (no rebuild needed).
bool same_layout(const GridConfig& a, const GridConfig& b);

struct FileOutcome {
  ErrorCode failure;              // none: done; else a MapError
  std::string message;            // what was done, or what went wrong (naming the file or robot)
  std::optional<MapImage> image;  // read_map_file: the decoded map
  bool ok() const { return failure == ErrorCode{}; }
  static FileOutcome failed(MapError kind, std::string message) { return {kind, std::move(message), {}}; }
};

// Writes the grid as <yaml_path> + <yaml_path>.pgm. The path must end in .yaml or .yml and its
// directory must exist (a remote request never creates directories).
FileOutcome export_map_file(const OccupancyGrid& grid, const std::string& yaml_path);
// Reads a ROS map: a missing/unreadable file is Io, a malformed one BadFile.
FileOutcome read_map_file(const std::string& yaml_path);

}  // namespace slam::mapper
