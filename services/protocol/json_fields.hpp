#pragma once
// Typed, bounded reads from a parsed JSON document (v2, VDA 5050). Each read names the field in its error
// ("pose.x is a string, expected a number"), and builds that name only when it fails, so the
// accepting path allocates nothing beyond the JSON document itself. Internal to robot_protocol.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>

#include "protocol/codec_types.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::protocol::json_fields {

using Json = nlohmann::json;

// Where a value sits, for messages: base, optional [index], optional .member ("points[3].x").
struct FieldName {
  static constexpr std::size_t kNoIndex = static_cast<std::size_t>(-1);
  constexpr FieldName(std::string_view b, std::size_t i = kNoIndex,
                      std::string_view m = {})  // NOLINT: braced use
      : base(b), index(i), member(m) {}
  std::string_view base;
  std::size_t index = kNoIndex;
  std::string_view member;
  std::string str() const;
};

// Parses `payload` (size-checked against limits) into `doc`, which must be a JSON object.
// JsonSyntax for malformed JSON or bad UTF-8, NonFinite for a number overflowing a double.
CodecStatus parse_object(std::span<const std::uint8_t> payload, const CodecLimits& limits, Json& doc);

// `object[key]`, or nullptr when absent. Optional fields treat JSON null as absent too.
const Json* find(const Json& object, std::string_view key);
const Json* find_optional(const Json& object, std::string_view key);
// `object[key]` or MissingField.
CodecStatus require(const Json& object, std::string_view key, const FieldName& name, const Json*& out);

// Type checks: JsonType naming the field and the type found.
CodecStatus expect_object(const Json& value, const FieldName& name);
CodecStatus expect_array(const Json& value, const FieldName& name);

// A number with |value| <= bound: JsonType, NonFinite or OutOfRange.
CodecStatus number(const Json& value, const FieldName& name, double bound, double& out);
// Required numeric member `key` of `object`.
CodecStatus member_number(const Json& object, std::string_view key, const FieldName& name, double bound,
                          double& out);
// Required string member: clean UTF-8 without control characters (BadText), at most max_bytes.
CodecStatus member_text(const Json& object, std::string_view key, const FieldName& name,
                        std::size_t max_bytes, std::string& out);
CodecStatus member_bool(const Json& object, std::string_view key, const FieldName& name, bool& out);
// Required unsigned integer member of at most 2^32 - 1 (OutOfRange).
CodecStatus member_uint32(const Json& object, std::string_view key, const FieldName& name,
                          std::uint32_t& out);
// Required array member of at most limits.max_points entries (TooManyPoints).
CodecStatus member_array(const Json& object, std::string_view key, const FieldName& name,
                         const CodecLimits& limits, const Json*& out);
// An [x, y] array of two coordinates within limits.max_abs_coordinate_m.
CodecStatus point_pair(const Json& value, const FieldName& name, const CodecLimits& limits, Point& out);

}  // namespace slam::protocol::json_fields
