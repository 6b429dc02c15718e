#pragma once
// Map interchange in the ROS map_server format (a YAML file naming a PGM image), shared by the mapper
// (export/import) and the simulator (worlds). Plain data in, plain data out: no grid types here.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/cell_class.hpp"
#include "common/core/result.hpp"

namespace slam {

// Trinary cell values of MapImage::cells: the grid's observed states, so images and grids copy 1:1.
inline constexpr uint8_t kMapUnknown = kCellUnknown;
inline constexpr uint8_t kMapFree = kCellFree;
inline constexpr uint8_t kMapOccupied = kCellOccupied;

// A decoded map. cells is row-major with row 0 at the BOTTOM (smallest y), like the grid; the PGM
// stores the top row first, and the reader/writer flip rows so callers never see PGM order.
struct MapImage {
  uint32_t width = 0;
  uint32_t height = 0;
  double resolution = 0.05;  // metres per pixel
  double origin_x = 0.0;     // map-frame position of the lower-left corner of pixel (0, 0)
  double origin_y = 0.0;
  double origin_yaw = 0.0;     // radians; map_server ignores it, we keep and honour it
  std::vector<uint8_t> cells;  // kMapUnknown / kMapFree / kMapOccupied
};

// The YAML part, as written in the file.
struct MapYaml {
  std::string image;  // path relative to the YAML file (or absolute)
  double resolution = 0.0;
  double origin[3] = {0.0, 0.0, 0.0};
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  std::string mode = "trinary";  // trinary or scale (classified the same way); raw is refused
};

// A PGM image (P5 binary or P2 ASCII), rows in file order (top first), samples scaled to 0..255.
struct PgmImage {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> pixels;
};

// Largest image accepted (pixels): bounds memory for hostile headers.
inline constexpr uint64_t kMaxMapPixels = uint64_t{1} << 28;

// `name` only labels error messages ("map.yaml: resolution must be > 0").
Result<MapYaml> parse_map_yaml(std::string_view text, std::string_view name);
Result<PgmImage> parse_pgm(std::span<const uint8_t> bytes, std::string_view name);
// Classifies pixels with the YAML thresholds and negate flag (map_server's rule) and flips rows.
Result<MapImage> decode_map(const MapYaml& yaml, const PgmImage& pgm, std::string_view name);

// The bytes write_ros_map puts in the files: P5 with 254 free, 0 occupied, 205 unknown, and the
// thresholds map_saver writes (0.65 / 0.196), which classify those three values back exactly.
std::vector<uint8_t> encode_pgm(const MapImage& map);
std::string encode_map_yaml(const MapImage& map, std::string_view image_name);

// Reads the YAML, then the image it names (relative paths resolve against the YAML's directory).
Result<MapImage> read_ros_map(const std::filesystem::path& yaml_path);
// Writes <yaml_path> and <yaml_path with extension .pgm> beside it.
Status write_ros_map(const std::filesystem::path& yaml_path, const MapImage& map);

}  // namespace slam
