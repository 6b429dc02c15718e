// Implementation of the bounded JSON field reads used by the v2 codec.
#include "protocol/json_fields.hpp"

#include <fmt/format.h>

#include <cmath>

#include "protocol/text_check.hpp"

namespace slam::protocol::json_fields {

std::string FieldName::str() const {
  std::string out(base);
  if (index != kNoIndex) out += fmt::format("[{}]", index);
  if (!member.empty()) {
    if (!out.empty()) out += '.';
    out += member;
  }
  return out;
}

CodecStatus parse_object(std::span<const std::uint8_t> payload, const CodecLimits& limits, Json& doc) {
  if (payload.empty()) return {RejectReason::EmptyPayload, "v2 payload is empty, expected a JSON object"};
  if (payload.size() > limits.max_payload_bytes)
    return {RejectReason::Oversized,
            fmt::format("payload is {} bytes, limit {}", payload.size(), limits.max_payload_bytes)};
  // Exceptions stay inside this function: they carry the byte offset and tell a syntax error from
  // a number overflow (1e999), which the no-throw parse mode would both report as "discarded".
  try {
    doc = Json::parse(payload.begin(), payload.end());
  } catch (const Json::parse_error& e) {
    return {RejectReason::JsonSyntax, fmt::format("invalid JSON near byte {}", e.byte)};
  } catch (const Json::out_of_range&) {
    return {RejectReason::NonFinite, "a number does not fit in a double"};
  } catch (const Json::exception& e) {
    return {RejectReason::JsonSyntax, fmt::format("invalid JSON (error {})", e.id)};
  }
  if (!doc.is_object())
    return {RejectReason::JsonType, fmt::format("top level is {}, expected an object", doc.type_name())};
  return CodecStatus::ok();
}

const Json* find(const Json& object, std::string_view key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

const Json* find_optional(const Json& object, std::string_view key) {
  const Json* value = find(object, key);
  return value != nullptr && value->is_null() ? nullptr : value;
}

CodecStatus require(const Json& object, std::string_view key, const FieldName& name, const Json*& out) {
  out = find(object, key);
  if (out == nullptr) return {RejectReason::MissingField, fmt::format("{} is missing", name.str())};
  return CodecStatus::ok();
}

CodecStatus expect_object(const Json& value, const FieldName& name) {
  if (value.is_object()) return CodecStatus::ok();
  return {RejectReason::JsonType, fmt::format("{} is {}, expected an object", name.str(), value.type_name())};
}

CodecStatus expect_array(const Json& value, const FieldName& name) {
  if (value.is_array()) return CodecStatus::ok();
  return {RejectReason::JsonType, fmt::format("{} is {}, expected an array", name.str(), value.type_name())};
}

CodecStatus number(const Json& value, const FieldName& name, double bound, double& out) {
  if (!value.is_number())
    return {RejectReason::JsonType,
            fmt::format("{} is {}, expected a number", name.str(), value.type_name())};
  const double v = value.get<double>();
  if (!std::isfinite(v)) return {RejectReason::NonFinite, fmt::format("{} is {}", name.str(), v)};
  if (std::abs(v) > bound)
    return {RejectReason::OutOfRange, fmt::format("{} is {}, limit +/-{}", name.str(), v, bound)};
  out = v;
  return CodecStatus::ok();
}

CodecStatus member_number(const Json& object, std::string_view key, const FieldName& name, double bound,
                          double& out) {
  const Json* value = nullptr;
  if (auto status = require(object, key, name, value); !status) return status;
  return number(*value, name, bound, out);
}

CodecStatus point_pair(const Json& value, const FieldName& name, const CodecLimits& limits, Point& out) {
  if (!value.is_array() || value.size() != 2)
    return {RejectReason::JsonType, fmt::format("{} is {}{}, expected [x, y]", name.str(), value.type_name(),
                                                value.is_array() ? fmt::format(" of {}", value.size()) : "")};
  const FieldName x{name.base, name.index, "x"};
  const FieldName y{name.base, name.index, "y"};
  if (auto status = number(value[0], x, limits.max_abs_coordinate_m, out.x); !status) return status;
  return number(value[1], y, limits.max_abs_coordinate_m, out.y);
}

CodecStatus member_text(const Json& object, std::string_view key, const FieldName& name,
                        std::size_t max_bytes, std::string& out) {
  const Json* value = nullptr;
  if (auto s = require(object, key, name, value); !s) return s;
  if (!value->is_string())
    return {RejectReason::JsonType,
            fmt::format("{} is {}, expected a string", name.str(), value->type_name())};
  const auto& text = value->get_ref<const std::string&>();
  if (text.size() > max_bytes)
    return {RejectReason::BadText,
            fmt::format("{} is {} bytes, limit {}", name.str(), text.size(), max_bytes)};
  if (const auto problem = find_text_problem(text))
    return {RejectReason::BadText,
            fmt::format("{} has {} at byte {}", name.str(), problem->what, problem->offset)};
  out = text;
  return CodecStatus::ok();
}

CodecStatus member_bool(const Json& object, std::string_view key, const FieldName& name, bool& out) {
  const Json* value = nullptr;
  if (auto s = require(object, key, name, value); !s) return s;
  if (!value->is_boolean())
    return {RejectReason::JsonType,
            fmt::format("{} is {}, expected a boolean", name.str(), value->type_name())};
  out = value->get<bool>();
  return CodecStatus::ok();
}

CodecStatus member_uint32(const Json& object, std::string_view key, const FieldName& name,
                          std::uint32_t& out) {
  const Json* value = nullptr;
  if (auto s = require(object, key, name, value); !s) return s;
  if (!value->is_number_unsigned() && !(value->is_number_integer() && value->get<std::int64_t>() >= 0))
    return {RejectReason::JsonType,
            fmt::format("{} is {}, expected an unsigned integer", name.str(), value->type_name())};
  const std::uint64_t v = value->get<std::uint64_t>();
  if (v > 0xFFFFFFFFu)
    return {RejectReason::OutOfRange, fmt::format("{} is {}, limit 4294967295", name.str(), v)};
  out = static_cast<std::uint32_t>(v);
  return CodecStatus::ok();
}

CodecStatus member_array(const Json& object, std::string_view key, const FieldName& name,
                         const CodecLimits& limits, const Json*& out) {
  if (auto s = require(object, key, name, out); !s) return s;
  if (auto s = expect_array(*out, name); !s) return s;
  if (out->size() > limits.max_points)
    return {RejectReason::TooManyPoints,
            fmt::format("{} has {} entries, limit {}", name.str(), out->size(), limits.max_points)};
  return CodecStatus::ok();
}

}  // namespace slam::protocol::json_fields
