// slam-mapper --export / --import / --export-trajectory (see mapper_offline.hpp).
#include "mapper/core/mapper_offline.hpp"

#include <filesystem>
#include <system_error>

#include "mapper/core/map_files.hpp"
#include "mapper/core/rebuild.hpp"
#include "mapper/core/trajectory_export.hpp"

namespace slam::mapper {
namespace {

Result<std::string> export_store(const MapperOptions& o, ObservationStore& store) {
  auto config = startup_config(o.grid, store);
  if (!config) return config.error();
  RebuildStats stats;
  auto grid = rebuild_grid(*config, store, &stats);
  if (!grid) return grid.error();
  FileOutcome out = export_map_file(*grid, o.export_yaml);
  if (!out.ok()) return Error{out.message};
  std::string summary = out.message + " (" + std::to_string(stats.observations) + " observations";
  if (stats.rejected > 0)
    summary += ", " + std::to_string(stats.rejected) + " rejected: " + stats.first_error;
  return summary + ")";
}

Result<std::string> export_trajectory(const MapperOptions& o, ObservationStore& store) {
  const auto format = trajectory_format_named(o.trajectory_format).value_or(TrajectoryFormat::Tum);
  FileOutcome out = export_trajectory_file(store, o.export_trajectory, o.trajectory_out, format);
  if (out.failure == MapError::UnknownRobot) return Error{out.message + " in " + o.store};
  if (!out.ok()) return Error{out.message};
  return out.message;
}

Result<std::string> import_prior(const MapperOptions& o, ObservationStore& store) {
  FileOutcome in = read_map_file(o.import_yaml);
  if (!in.ok()) return Error{in.message};
  if (Status s = store.save_prior(*in.image); !s) return s.error();
  return in.message + "; stored as the prior of " + o.store;
}

}  // namespace

Result<std::string> run_offline(const MapperOptions& o) {
  std::error_code ec;
  const bool exports = !o.export_yaml.empty() || !o.export_trajectory.empty();
  if (exports && !std::filesystem::is_regular_file(o.store, ec))
    return Error{"observation store " + o.store + ": no such file (nothing to export)"};
  auto store = open_store(o.store, StoreOptions{o.store_batch});
  if (!store) return store.error();
  if (!o.export_trajectory.empty()) return export_trajectory(o, *store);
  return o.export_yaml.empty() ? import_prior(o, *store) : export_store(o, *store);
}

}  // namespace slam::mapper
