#pragma once
// Why the gateway refused a message: a closed set of reasons so every rejection lands in a named
// counter ("rejected_bad_length") and a log line that says what exactly was wrong.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

namespace slam::protocol {

enum class RejectReason : std::uint8_t {
  EmptyPayload,   // zero-length payload
  Oversized,      // payload larger than CodecLimits::max_payload_bytes
  BadLength,      // v1 length not a multiple of 4, or scan angles/ranges counts differ
  TooManyPoints,  // more obstacle points or beams than CodecLimits::max_points
  UnknownTopic,   // topic outside the v1/v2 trees and the VDA 5050 robot topics
  BadRobotId,     // robot id empty, too long, wildcard or '/', control character, bad UTF-8
  JsonSyntax,     // not JSON (includes invalid UTF-8 inside JSON strings)
  JsonType,       // JSON of the wrong shape: not an object, a string where a number belongs, ...
  MissingField,   // a required field is absent
  NonFinite,      // NaN, infinity, or a number too large for a double
  OutOfRange,     // a finite number outside its allowed range (coordinates, battery, int16, ...)
  BadText,        // a text field that is empty, too long or holds control characters
  BadVersion,     // a VDA 5050 message whose version is not the major version configured
  UnknownRobot,   // a VDA 5050 message from a robot outside the configured list
};

inline constexpr std::size_t kRejectReasonCount = 14;

// Every reason, in enum order: lets a service register all counters at start.
inline constexpr std::array<RejectReason, kRejectReasonCount> kAllRejectReasons = {
    RejectReason::EmptyPayload,  RejectReason::Oversized,    RejectReason::BadLength,
    RejectReason::TooManyPoints, RejectReason::UnknownTopic, RejectReason::BadRobotId,
    RejectReason::JsonSyntax,    RejectReason::JsonType,     RejectReason::MissingField,
    RejectReason::NonFinite,     RejectReason::OutOfRange,   RejectReason::BadText,
    RejectReason::BadVersion,    RejectReason::UnknownRobot};

// Stable snake_case name, e.g. "bad_length". Part of the operator-facing contract: never rename.
std::string_view reason_name(RejectReason reason);
// Counter name, e.g. "rejected_bad_length".
std::string_view reason_counter(RejectReason reason);
// One-line human description, e.g. "payload length is not a multiple of 4 bytes".
std::string_view reason_description(RejectReason reason);

// Outcome of a codec call: ok, or a reason plus a detail naming the offending field or value.
// The ok path holds an empty string, so returning it never allocates.
class [[nodiscard]] CodecStatus {
 public:
  CodecStatus() = default;
  CodecStatus(RejectReason reason, std::string detail)
      : detail_(std::move(detail)), reason_(reason), failed_(true) {}
  static CodecStatus ok() { return {}; }

  bool is_ok() const { return !failed_; }
  explicit operator bool() const { return !failed_; }
  // Meaningful only when !is_ok().
  RejectReason reason() const { return reason_; }
  const std::string& detail() const { return detail_; }
  // "bad_length: payload is 7 bytes, not a multiple of 4"; "ok" when ok.
  std::string message() const;

 private:
  std::string detail_;
  RejectReason reason_ = RejectReason::EmptyPayload;
  bool failed_ = false;
};

}  // namespace slam::protocol
