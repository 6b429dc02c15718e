#pragma once
// bench_pipeline's Foxglove client (SLAM_BENCH_PIPELINE_BRIDGE=1): one WebSocket connection to
// slam-bridge that subscribes to every channel the bridge advertises, as Foxglove does when a layout
// shows everything, and counts what arrives. Built as C++17 like the bridge's own WebSocket edge
// (websocketpp 0.8 does not compile as C++20), so this header includes only the standard library
// and result.hpp.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "common/core/result.hpp"

namespace slam::bench {

class BridgeClient {
 public:
  // Connects to ws://127.0.0.1:port with the foxglove.websocket.v1 subprotocol and runs its own
  // I/O thread; subscribes to each channel as the bridge advertises it.
  static Result<std::unique_ptr<BridgeClient>> connect(uint16_t port);
  ~BridgeClient();  // closes the connection and joins the I/O thread
  BridgeClient(const BridgeClient&) = delete;
  BridgeClient& operator=(const BridgeClient&) = delete;

  struct Totals {
    uint32_t channels = 0;     // channels advertised (and subscribed)
    uint64_t messages = 0;     // binary message frames received
    uint64_t bytes = 0;        // their bytes
    uint64_t text_frames = 0;  // JSON ops received (serverInfo, advertise, status, ...)
    bool open = false;         // the connection is open
  };
  Totals totals() const;

  // Waits until at least `channels` channels are subscribed; false at the timeout or on a closed
  // connection.
  bool wait_subscribed(uint32_t channels, std::chrono::milliseconds timeout) const;

 private:
  struct Impl;
  explicit BridgeClient(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace slam::bench
