// World selection by spec, and the adapter from the shared ROS map reader to occupancy images.
#include "simulator/core/world_loader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "simulator/core/builtin_worlds.hpp"
#include "simulator/core/world_image.hpp"
#include "simulator/core/world_text.hpp"

namespace slam::sim {

Result<World> world_from_map(const MapImage& map, std::string name) {
  if (map.origin_yaw != 0.0)
    return Error{fmt::format("map '{}': origin yaw {} rad is not supported for simulator worlds (must be 0)",
                             name, map.origin_yaw)};
  OccupancyImage image;
  image.width = static_cast<int>(std::min<uint32_t>(map.width, 1u << 30));
  image.height = static_cast<int>(std::min<uint32_t>(map.height, 1u << 30));
  image.resolution = map.resolution;
  image.origin = {map.origin_x, map.origin_y};
  image.occupied.resize(map.cells.size());
  std::transform(map.cells.begin(), map.cells.end(), image.occupied.begin(),
                 [](uint8_t c) { return static_cast<uint8_t>(c == kMapOccupied ? 1 : 0); });
  return world_from_image(image, std::move(name));
}

Result<World> load_world(std::string_view spec) {
  const auto names = builtin_world_names();
  if (std::find(names.begin(), names.end(), spec) != names.end()) return builtin_world(spec);
  const std::filesystem::path path{std::string(spec)};
  const auto ext = path.extension().string();
  if (ext == ".yaml" || ext == ".yml") {
    auto map = read_ros_map(path);
    if (!map) return map.error();
    return world_from_map(*map, path.stem().string());
  }
  if (spec.empty())
    return Error{fmt::format("no world given (a built-in name: {}, a .yaml map or a .txt world)",
                             fmt::join(names, ", "))};
  return load_java_world(path);
}

}  // namespace slam::sim
