#pragma once
// One entry point for everything robots send: the service parses the topic, then hands the
// payload here with the topic's kind. The output is reused message after message.
#include <cstdint>
#include <span>

#include "protocol/codec_types.hpp"
#include "protocol/reject_reason.hpp"
#include "protocol/topic.hpp"

namespace slam::protocol {

struct DecodedMessage {
  TopicKind kind = TopicKind::V1Adv;
  DecodedObservation observation;  // filled for V1Adv, V2Pose, V2Points, V2Scan
  DecodedStatus status;            // filled for V2Status
};

// Decodes `payload` as `kind` into out (out.kind = kind; the unused member is cleared).
CodecStatus decode_message(TopicKind kind, std::span<const std::uint8_t> payload, const CodecLimits& limits,
                           DecodedMessage& out);

}  // namespace slam::protocol
