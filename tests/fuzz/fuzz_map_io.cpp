// Fuzz target for the ROS map reader: the input is "<yaml>\0<pgm bytes>". Whatever parses must
// survive an encode/decode round trip unchanged; nothing may crash, hang or allocate unboundedly.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <string_view>

#include "common/core/map_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto* split = static_cast<const uint8_t*>(std::memchr(data, 0, size));
  const size_t yaml_len = split ? static_cast<size_t>(split - data) : size;
  const std::string_view yaml_text(reinterpret_cast<const char*>(data), yaml_len);
  const std::span<const uint8_t> pgm_bytes =
      split ? std::span<const uint8_t>(split + 1, size - yaml_len - 1) : std::span<const uint8_t>();

  auto yaml = slam::parse_map_yaml(yaml_text, "fuzz.yaml");
  auto pgm = slam::parse_pgm(pgm_bytes, "fuzz.pgm");
  if (!yaml || !pgm) return 0;
  auto map = slam::decode_map(*yaml, *pgm, "fuzz.pgm");
  if (!map) return 0;

  const std::vector<uint8_t> encoded = slam::encode_pgm(*map);
  auto pgm2 = slam::parse_pgm(encoded, "again.pgm");
  auto yaml2 = slam::parse_map_yaml(slam::encode_map_yaml(*map, "again.pgm"), "again.yaml");
  if (!pgm2 || !yaml2) std::abort();
  auto map2 = slam::decode_map(*yaml2, *pgm2, "again.pgm");
  if (!map2 || map2->cells != map->cells || map2->resolution != map->resolution ||
      map2->origin_x != map->origin_x || map2->origin_y != map->origin_y ||
      map2->origin_yaw != map->origin_yaw)
    std::abort();
  return 0;
}
