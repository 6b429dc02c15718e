#pragma once
// The framing of the Foxglove WebSocket protocol (subprotocol foxglove.websocket.v1): the JSON
// operations the server sends, and the binary frames both ways (little-endian). Plain C++: the
// WebSocket edge only moves these bytes.
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "common/core/result.hpp"

namespace slam::bridge::foxglove {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

// Server binary opcodes.
inline constexpr uint8_t kMessageData = 0x01;
inline constexpr uint8_t kServiceCallResponse = 0x03;
// Client binary opcodes.
inline constexpr uint8_t kClientMessageData = 0x01;
inline constexpr uint8_t kServiceCallRequest = 0x02;

enum class StatusLevel : uint8_t { Info = 0, Warning = 1, Error = 2 };

struct ChannelInfo {
  uint32_t id = 0;
  std::string topic;
  std::string encoding;  // "json"
  std::string schema_name;
  std::string schema;           // the JSON schema text
  std::string schema_encoding;  // "jsonschema"
};

struct ServiceInfo {
  uint32_t id = 0;
  std::string name;
  std::string type;
  std::string request_schema_name;
  std::string request_schema;
  std::string response_schema_name;
  std::string response_schema;
};

std::string server_info(const std::string& name, const std::vector<std::string>& capabilities,
                        const std::vector<std::string>& supported_encodings, const std::string& session_id);
std::string advertise(const std::vector<ChannelInfo>& channels);
std::string advertise_services(const std::vector<ServiceInfo>& services);
std::string status(StatusLevel level, const std::string& message);
std::string service_call_failure(uint32_t service_id, uint32_t call_id, const std::string& message);

// Binary frames from the server.
std::string message_data(uint32_t subscription_id, uint64_t timestamp_ns, std::string_view payload);
std::string service_call_response(uint32_t service_id, uint32_t call_id, std::string_view encoding,
                                  std::string_view payload);

// Binary frames from a client.
struct ClientMessageData {
  uint32_t channel_id = 0;
  std::string_view payload;
};
struct ServiceCallRequest {
  uint32_t service_id = 0;
  uint32_t call_id = 0;
  std::string_view encoding;
  std::string_view payload;
};
using ClientBinary = std::variant<ClientMessageData, ServiceCallRequest>;

// The views point into `frame`.
Result<ClientBinary> parse_client_binary(std::string_view frame);

}  // namespace slam::bridge::foxglove
