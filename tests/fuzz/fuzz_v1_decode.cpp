// Fuzz target for the v1 binary codec. Beyond "no crash" it checks what must hold: an accepted
// payload has k - 1 finite, bounded obstacle points and re-encodes to the very same bytes, and
// any waypoint the encoder accepts decodes back within half a robot unit.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <vector>

#include "protocol/v1_codec.hpp"

namespace {

using namespace slam::protocol;

void check(bool condition) {
  if (!condition) std::abort();
}

void check_decoded(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                   const DecodedObservation& out) {
  check(out.has_pose && !out.has_heading && out.misses.empty());
  check(out.hits.size() == payload.size() / kV1PairBytes - 1 && out.hits.size() <= limits.max_points);
  auto bounded = [&](double v) { return std::isfinite(v) && std::abs(v) <= limits.max_abs_coordinate_m; };
  check(bounded(out.x) && bounded(out.y));
  for (const Point& p : out.hits) check(bounded(p.x) && bounded(p.y));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::span<const std::uint8_t> payload(data, size);

  static DecodedObservation out;  // reused like the gateway does
  static std::vector<std::uint8_t> re_encoded;
  const CodecLimits defaults;
  if (decode_v1(payload, defaults, out)) {
    check_decoded(payload, defaults, out);
    check(encode_v1_adv({out.x, out.y}, out.hits, defaults.units_per_meter, re_encoded).is_ok());
    check(re_encoded.size() == size && std::memcmp(re_encoded.data(), data, size) == 0);
  }

  // Tight limits reach the too-many-points and out-of-range paths with ordinary inputs.
  CodecLimits tight;
  tight.units_per_meter = 1.0;
  tight.max_abs_coordinate_m = 1000.0;
  tight.max_points = 8;
  tight.max_payload_bytes = 64;
  if (decode_v1(payload, tight, out)) check_decoded(payload, tight, out);

  // The first 16 bytes as two doubles (any bit pattern: NaN, inf, huge) through the encoder.
  if (size >= 2 * sizeof(double)) {
    Point waypoint;
    std::memcpy(&waypoint.x, data, sizeof(double));
    std::memcpy(&waypoint.y, data + sizeof(double), sizeof(double));
    std::array<std::uint8_t, kV1PairBytes> bytes{};
    if (encode_v1_waypoint(waypoint, defaults.units_per_meter, bytes)) {
      check(decode_v1(bytes, defaults, out).is_ok());
      const double half_unit = 0.5 / defaults.units_per_meter + 1e-9;
      check(std::abs(out.x - waypoint.x) <= half_unit && std::abs(out.y - waypoint.y) <= half_unit);
    }
  }
  return 0;
}
