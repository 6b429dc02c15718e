// Names and descriptions of rejection reasons, kept in one table so names cannot drift apart.
#include "protocol/reject_reason.hpp"

namespace slam::protocol {
namespace {

struct ReasonText {
  std::string_view name;
  std::string_view counter;
  std::string_view description;
};

constexpr std::array<ReasonText, kRejectReasonCount> kTexts = {{
    {"empty_payload", "rejected_empty_payload", "payload is empty"},
    {"oversized", "rejected_oversized", "payload is larger than the configured limit"},
    {"bad_length", "rejected_bad_length",
     "a length is wrong (v1 payload not a multiple of 4 bytes, or array sizes differ)"},
    {"too_many_points", "rejected_too_many_points", "message has more points than the configured limit"},
    {"unknown_topic", "rejected_unknown_topic", "topic is not part of the v1, v2 or VDA 5050 robot trees"},
    {"bad_robot_id", "rejected_bad_robot_id",
     "robot id is empty, too long, has wildcards, '/', control characters or bad UTF-8"},
    {"json_syntax", "rejected_json_syntax", "payload is not valid JSON"},
    {"json_type", "rejected_json_type", "JSON value has the wrong type or shape"},
    {"missing_field", "rejected_missing_field", "a required JSON field is missing"},
    {"non_finite", "rejected_non_finite", "a number is NaN, infinite or too large"},
    {"out_of_range", "rejected_out_of_range", "a number is outside its allowed range"},
    {"bad_text", "rejected_bad_text", "a text field is empty, too long or has control characters"},
    {"bad_version", "rejected_bad_version", "VDA 5050 message of another major version"},
    {"unknown_robot", "rejected_unknown_robot", "VDA 5050 message from a robot not configured as one"},
}};

const ReasonText& text(RejectReason reason) {
  return kTexts[static_cast<std::size_t>(reason)];
}

}  // namespace

std::string_view reason_name(RejectReason reason) {
  return text(reason).name;
}
std::string_view reason_counter(RejectReason reason) {
  return text(reason).counter;
}
std::string_view reason_description(RejectReason reason) {
  return text(reason).description;
}

std::string CodecStatus::message() const {
  if (!failed_) return "ok";
  std::string out(reason_name(reason_));
  out += ": ";
  out += detail_.empty() ? reason_description(reason_) : std::string_view(detail_);
  return out;
}

}  // namespace slam::protocol
