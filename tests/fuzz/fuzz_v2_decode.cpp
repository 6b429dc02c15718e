// Fuzz target for the topic parser and the v2 JSON decoders. Input: "<topic>\n<payload>". The
// topic goes through parse_topic() and, when accepted, selects the decoder; the payload also goes
// through every v2 decoder regardless, so a mutated topic does not hide the JSON paths. Accepted
// output must be finite, bounded (robot stamps too) and within the count limits; paths must
// re-encode exactly.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <string_view>

#include "fuzz_topic_input.hpp"
#include "protocol/message_decoder.hpp"
#include "protocol/text_check.hpp"
#include "protocol/topic.hpp"
#include "protocol/v2_robot_decode.hpp"
#include "protocol/v2_server_codec.hpp"

namespace {

using namespace slam::protocol;

void check(bool condition) {
  if (!condition) std::abort();
}

bool bounded(double v, const CodecLimits& limits) {
  return std::isfinite(v) && std::abs(v) <= limits.max_abs_coordinate_m;
}

void check_observation(const DecodedObservation& out, const CodecLimits& limits) {
  if (out.has_pose) check(bounded(out.x, limits) && bounded(out.y, limits));
  check(std::isfinite(out.theta));
  check(out.robot_stamp_ns >= 0 && static_cast<double>(out.robot_stamp_ns) <= kMaxRobotStampS * 1e9);
  check(out.hits.size() + out.misses.size() <= limits.max_points);
  for (const Point& p : out.hits) check(bounded(p.x, limits) && bounded(p.y, limits));
  for (const Point& p : out.misses) check(bounded(p.x, limits) && bounded(p.y, limits));
}

void check_status(const DecodedStatus& out) {
  check(!out.state.empty() && out.state.size() <= kMaxStateBytes && !find_text_problem(out.state));
  check(out.battery <= 1.0f && (out.battery >= 0.0f || out.battery == -1.0f));
  check(out.offline == (out.state == "offline"));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto [topic, payload] = slam::fuzz::split_topic_input(data, size);

  CodecLimits limits;
  limits.max_points = 64;  // small enough for the fuzzer to reach the limit

  static DecodedMessage message;
  ParsedTopic parsed;
  if (parse_topic(topic, parsed)) {
    check(validate_robot_id(parsed.robot_id).is_ok());
    std::string rebuilt;
    check(v1_command_topic(parsed.robot_id, rebuilt).is_ok());
    if (decode_message(parsed.kind, payload, limits, message)) {
      check(message.kind == parsed.kind);
      if (parsed.kind == TopicKind::V2Status)
        check_status(message.status);
      else
        check_observation(message.observation, limits);
    }
  }

  static DecodedObservation observation;
  for (auto decode : {decode_v2_pose, decode_v2_points, decode_v2_scan})
    if (decode(payload, limits, observation)) check_observation(observation, limits);
  static DecodedStatus status;
  if (decode_v2_status(payload, limits, status)) check_status(status);

  static V2Waypoint waypoint;
  if (decode_v2_waypoint(payload, limits, waypoint))
    check(bounded(waypoint.waypoint.x, limits) && bounded(waypoint.waypoint.y, limits));
  static V2Path path;
  static V2Path again;
  static std::string text;
  if (decode_v2_path(payload, limits, path)) {
    check(encode_v2_path(path.seq, path.points, limits, text).is_ok());
    const std::span<const std::uint8_t> encoded(reinterpret_cast<const std::uint8_t*>(text.data()),
                                                text.size());
    check(decode_v2_path(encoded, limits, again).is_ok());
    check(again.seq == path.seq && again.points == path.points);
  }
  return 0;
}
