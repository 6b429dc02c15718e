// Store opening, start-up layout and ROS map files for the mapper (see map_files.hpp).
#include "mapper/core/map_files.hpp"

#include <system_error>

namespace slam::mapper {
namespace {

// Remote requests name files on the mapper's disk: refuse what cannot be a map path before touching it.
std::optional<FileOutcome> check_path(const std::string& yaml_path) {
  if (yaml_path.empty()) return FileOutcome::failed(MapError::InvalidRequest, "yaml_path is empty");
  if (yaml_path.find('\0') != std::string::npos)
    return FileOutcome::failed(MapError::InvalidRequest, "yaml_path contains a NUL character");
  const std::filesystem::path p(yaml_path);
  const std::string ext = p.extension().string();
  if (ext != ".yaml" && ext != ".yml")
    return FileOutcome::failed(MapError::InvalidRequest,
                               "yaml_path '" + yaml_path + "' must end in .yaml or .yml");
  return std::nullopt;
}

}  // namespace

Result<ObservationStore> open_store(const std::filesystem::path& path, StoreOptions options) {
  const std::filesystem::path dir = path.parent_path();
  if (!dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec)
      return Error{"observation store " + path.string() + ": cannot create directory " + dir.string() + ": " +
                   ec.message()};
  }
  return ObservationStore::open(path, options);
}

Result<GridConfig> startup_config(const GridConfig& defaults, ObservationStore& store) {
  auto stored = store.load_config();
  if (!stored) return stored.error();
  GridConfig config = defaults;
  if (stored->has_value()) {
    const GridConfig& s = **stored;
    config.resolution = s.resolution;
    config.origin_x = s.origin_x;
    config.origin_y = s.origin_y;
    config.width_m = s.width_m;
    config.height_m = s.height_m;
    config.inflation_radius = s.inflation_radius;
    config.legacy_mode = s.legacy_mode;
  }
  if (Status v = validate(config); !v)
    return Error{"observation store " + store.path().string() +
                 ": its layout does not fit the grid flags: " + v.message()};
  return config;
}

bool same_layout(const GridConfig& a, const GridConfig& b) {
  return a.resolution == b.resolution && a.origin_x == b.origin_x && a.origin_y == b.origin_y &&
         a.width_m == b.width_m && a.height_m == b.height_m && a.inflation_radius == b.inflation_radius &&
         a.legacy_mode == b.legacy_mode;
}

FileOutcome export_map_file(const OccupancyGrid& grid, const std::string& yaml_path) {
  if (auto bad = check_path(yaml_path)) return *bad;
  const std::filesystem::path p(yaml_path);
  const std::filesystem::path dir = p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    return FileOutcome::failed(MapError::Io, "directory " + dir.string() + " does not exist");
  const MapImage image = grid.to_map_image();
  if (Status s = write_ros_map(p, image); !s) return FileOutcome::failed(MapError::Io, s.message());
  std::filesystem::path pgm = p;
  pgm.replace_extension(".pgm");
  return FileOutcome{{},
                     "exported " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " cells at " + std::to_string(image.resolution) + " m to " + yaml_path + " and " +
                         pgm.string(),
                     {}};
}

FileOutcome read_map_file(const std::string& yaml_path) {
  if (auto bad = check_path(yaml_path)) return *bad;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(yaml_path, ec))
    return FileOutcome::failed(MapError::Io, yaml_path + ": no such file");
  auto image = read_ros_map(yaml_path);
  // The YAML exists: what fails now is its content or the image it names.
  if (!image) return FileOutcome::failed(MapError::BadFile, image.message());
  FileOutcome out{{},
                  "read " + std::to_string(image->width) + "x" + std::to_string(image->height) +
                      " pixels at " + std::to_string(image->resolution) + " m from " + yaml_path,
                  std::move(*image)};
  return out;
}

}  // namespace slam::mapper
