// Dispatch from topic kind to decoder, so the service has a single call per inbound message.
#include "protocol/message_decoder.hpp"

#include "protocol/v1_codec.hpp"
#include "protocol/v2_robot_decode.hpp"

namespace slam::protocol {

CodecStatus decode_message(TopicKind kind, std::span<const std::uint8_t> payload, const CodecLimits& limits,
                           DecodedMessage& out) {
  out.kind = kind;
  out.observation.clear();
  out.status.clear();
  switch (kind) {
    case TopicKind::V1Adv:
      return decode_v1(payload, limits, out.observation);
    case TopicKind::V2Pose:
      return decode_v2_pose(payload, limits, out.observation);
    case TopicKind::V2Points:
      return decode_v2_points(payload, limits, out.observation);
    case TopicKind::V2Scan:
      return decode_v2_scan(payload, limits, out.observation);
    case TopicKind::V2Status:
      return decode_v2_status(payload, limits, out.status);
  }
  return {RejectReason::UnknownTopic, "unknown topic kind"};
}

}  // namespace slam::protocol
