#pragma once
// The bridge's WebSocket edge (websocketpp on standalone asio, one I/O thread): accepts clients that
// offer the foxglove.websocket.v1 subprotocol, queues what they send as events for the service loop,
// and sends what the Foxglove face gives it. No DDS, no protocol logic: the face decides every byte.
// Compiled as C++17 (websocketpp 0.8's headers are not valid C++20), so this header and its source
// include nothing of the C++20 core but result.hpp.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/core/result.hpp"

namespace slam::bridge {

// A client's number, as the Foxglove face knows it (bridge::ClientId).
using WsClientId = uint64_t;

struct ClientEvent {
  enum class Kind { Connected, Disconnected, Text, Binary };
  Kind kind = Kind::Connected;
  WsClientId client = 0;
  std::string bytes;
};

class WsServer {
 public:
  // Listens on host:port and starts the I/O thread; an error when the address cannot be bound. Only
  // clients offering `subprotocol` are accepted. Data messages dropped for a slow client are
  // counted in `dropped`.
  static Result<std::unique_ptr<WsServer>> start(const std::string& host, uint16_t port,
                                                 const std::string& subprotocol, uint32_t backlog_bytes,
                                                 std::atomic<int64_t>& dropped);
  ~WsServer();  // closes every connection and joins the I/O thread
  WsServer(const WsServer&) = delete;
  WsServer& operator=(const WsServer&) = delete;

  // Everything clients did since the last call, in order.
  std::vector<ClientEvent> take_events();

  void send_text(WsClientId client, const std::string& text);
  // Dropped (and counted) while the client has more than backlog_bytes unsent.
  void send_binary(WsClientId client, const std::string& bytes);

  uint16_t port() const;

 private:
  struct Impl;
  explicit WsServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace slam::bridge
