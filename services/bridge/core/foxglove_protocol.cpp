// Foxglove WebSocket protocol framing (see foxglove_protocol.hpp).
#include "bridge/core/foxglove_protocol.hpp"

#include <nlohmann/json.hpp>

namespace slam::bridge::foxglove {
namespace {

using nlohmann::json;

void put_u32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

void put_u64(std::string& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

// Reads a little-endian u32 at `offset`, advancing it; false when the frame is too short.
bool get_u32(std::string_view frame, size_t& offset, uint32_t& v) {
  if (frame.size() < offset + 4) return false;
  v = 0;
  for (int i = 0; i < 4; ++i) v |= uint32_t{static_cast<uint8_t>(frame[offset + i])} << (8 * i);
  offset += 4;
  return true;
}

}  // namespace

std::string server_info(const std::string& name, const std::vector<std::string>& capabilities,
                        const std::vector<std::string>& supported_encodings, const std::string& session_id) {
  return json{{"op", "serverInfo"},           {"name", name},
              {"capabilities", capabilities}, {"supportedEncodings", supported_encodings},
              {"metadata", json::object()},   {"sessionId", session_id}}
      .dump();
}

std::string advertise(const std::vector<ChannelInfo>& channels) {
  json list = json::array();
  for (const ChannelInfo& c : channels)
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", c.encoding},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", c.schema_encoding}});
  return json{{"op", "advertise"}, {"channels", std::move(list)}}.dump();
}

std::string advertise_services(const std::vector<ServiceInfo>& services) {
  json list = json::array();
  for (const ServiceInfo& s : services)
    list.push_back({{"id", s.id},
                    {"name", s.name},
                    {"type", s.type},
                    {"request",
                     {{"encoding", "json"},
                      {"schemaName", s.request_schema_name},
                      {"schemaEncoding", "jsonschema"},
                      {"schema", s.request_schema}}},
                    {"response",
                     {{"encoding", "json"},
                      {"schemaName", s.response_schema_name},
                      {"schemaEncoding", "jsonschema"},
                      {"schema", s.response_schema}}}});
  return json{{"op", "advertiseServices"}, {"services", std::move(list)}}.dump();
}

std::string status(StatusLevel level, const std::string& message) {
  return json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump();
}

std::string service_call_failure(uint32_t service_id, uint32_t call_id, const std::string& message) {
  return json{
      {"op", "serviceCallFailure"}, {"serviceId", service_id}, {"callId", call_id}, {"message", message}}
      .dump();
}

std::string message_data(uint32_t subscription_id, uint64_t timestamp_ns, std::string_view payload) {
  std::string out;
  out.reserve(13 + payload.size());
  out += static_cast<char>(kMessageData);
  put_u32(out, subscription_id);
  put_u64(out, timestamp_ns);
  out += payload;
  return out;
}

std::string service_call_response(uint32_t service_id, uint32_t call_id, std::string_view encoding,
                                  std::string_view payload) {
  std::string out;
  out.reserve(13 + encoding.size() + payload.size());
  out += static_cast<char>(kServiceCallResponse);
  put_u32(out, service_id);
  put_u32(out, call_id);
  put_u32(out, static_cast<uint32_t>(encoding.size()));
  out += encoding;
  out += payload;
  return out;
}

Result<ClientBinary> parse_client_binary(std::string_view frame) {
  if (frame.empty()) return Error{"empty binary message"};
  size_t offset = 1;
  switch (static_cast<uint8_t>(frame[0])) {
    case kClientMessageData: {
      ClientMessageData m;
      if (!get_u32(frame, offset, m.channel_id)) return Error{"client message data shorter than its header"};
      m.payload = frame.substr(offset);
      return ClientBinary{m};
    }
    case kServiceCallRequest: {
      ServiceCallRequest r;
      uint32_t encoding_length = 0;
      if (!get_u32(frame, offset, r.service_id) || !get_u32(frame, offset, r.call_id) ||
          !get_u32(frame, offset, encoding_length) || frame.size() - offset < encoding_length)
        return Error{"service call request shorter than its header"};
      r.encoding = frame.substr(offset, encoding_length);
      r.payload = frame.substr(offset + encoding_length);
      return ClientBinary{r};
    }
    default:
      return Error{"unknown binary opcode " + std::to_string(static_cast<uint8_t>(frame[0]))};
  }
}

}  // namespace slam::bridge::foxglove
