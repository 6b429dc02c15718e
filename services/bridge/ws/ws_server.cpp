// The WebSocket edge (see ws_server.hpp).
#include "bridge/ws/ws_server.hpp"

#include <spdlog/spdlog.h>

#include <map>
#include <mutex>
#include <thread>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "common/core/guarded_callback.hpp"

namespace slam::bridge {

using Server = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

struct WsServer::Impl {
  Server server;
  std::thread io;
  std::atomic<bool> io_done{false};
  std::string subprotocol;
  uint32_t backlog_bytes = 0;
  std::atomic<int64_t>& dropped;

  std::mutex mutex;  // guards everything below (I/O thread vs the service loop)
  std::vector<ClientEvent> events;
  std::map<Handle, WsClientId, std::owner_less<Handle>> ids;
  std::map<WsClientId, Handle> handles;
  WsClientId next_id = 1;

  explicit Impl(std::atomic<int64_t>& dropped_counter) : dropped(dropped_counter) {}

  void push(ClientEvent::Kind kind, Handle hdl, std::string bytes = {}) {
    std::lock_guard lock(mutex);
    WsClientId id = 0;
    if (kind == ClientEvent::Kind::Connected) {
      id = next_id++;
      ids[hdl] = id;
      handles[id] = hdl;
    } else {
      const auto it = ids.find(hdl);
      if (it == ids.end()) return;
      id = it->second;
      if (kind == ClientEvent::Kind::Disconnected) {
        handles.erase(id);
        ids.erase(it);
      }
    }
    events.push_back({kind, id, std::move(bytes)});
  }

  // The connection of `client`, or nothing when it is gone.
  Server::connection_ptr connection(WsClientId client) {
    Handle hdl;
    {
      std::lock_guard lock(mutex);
      const auto it = handles.find(client);
      if (it == handles.end()) return nullptr;
      hdl = it->second;
    }
    websocketpp::lib::error_code ec;
    auto con = server.get_con_from_hdl(hdl, ec);
    return ec ? nullptr : con;
  }

  void send(WsClientId client, const std::string& bytes, websocketpp::frame::opcode::value op,
            bool droppable) {
    auto con = connection(client);
    if (!con) return;
    if (droppable && con->get_buffered_amount() > backlog_bytes) {
      dropped.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    const auto ec = con->send(bytes, op);
    if (ec) spdlog::debug("bridge: send to client {} failed: {}", client, ec.message());
  }
};

WsServer::WsServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

Result<std::unique_ptr<WsServer>> WsServer::start(const std::string& host, uint16_t port,
                                                  const std::string& subprotocol, uint32_t backlog_bytes,
                                                  std::atomic<int64_t>& dropped) {
  auto impl = std::make_unique<Impl>(dropped);
  impl->subprotocol = subprotocol;
  impl->backlog_bytes = backlog_bytes;
  Impl* p = impl.get();
  Server& s = p->server;
  s.clear_access_channels(websocketpp::log::alevel::all);
  s.clear_error_channels(websocketpp::log::elevel::all);
  websocketpp::lib::error_code ec;
  s.init_asio(ec);
  if (ec) return Error{"websocket: " + ec.message()};
  s.set_reuse_addr(true);
  // Only clients that speak the protocol get in; the subprotocol is echoed as the spec requires.
  s.set_validate_handler([p](Handle hdl) {
    bool accept = false;
    guarded_callback("websocket validate", [&] {
      auto con = p->server.get_con_from_hdl(hdl);
      for (const std::string& offered : con->get_requested_subprotocols())
        if (offered == p->subprotocol) {
          con->select_subprotocol(offered);
          accept = true;
          return;
        }
      spdlog::info("bridge: refused a client that does not offer {}", p->subprotocol);
    });
    return accept;
  });
  s.set_open_handler([p](Handle hdl) {
    guarded_callback("websocket open", [&] { p->push(ClientEvent::Kind::Connected, hdl); });
  });
  s.set_close_handler([p](Handle hdl) {
    guarded_callback("websocket close", [&] { p->push(ClientEvent::Kind::Disconnected, hdl); });
  });
  s.set_fail_handler([p](Handle hdl) {
    guarded_callback("websocket fail", [&] { p->push(ClientEvent::Kind::Disconnected, hdl); });
  });
  s.set_message_handler([p](Handle hdl, Server::message_ptr msg) {
    guarded_callback("websocket message", [&] {
      const bool text = msg->get_opcode() == websocketpp::frame::opcode::text;
      p->push(text ? ClientEvent::Kind::Text : ClientEvent::Kind::Binary, hdl,
              std::move(msg->get_raw_payload()));
    });
  });

  asio::ip::address address = asio::ip::make_address(host, ec);
  if (ec) return Error{"bind address '" + host + "': " + ec.message()};
  s.listen(asio::ip::tcp::endpoint(address, port), ec);
  if (ec) return Error{"cannot listen on " + host + ":" + std::to_string(port) + ": " + ec.message()};
  s.start_accept(ec);
  if (ec) return Error{"websocket accept: " + ec.message()};
  p->io = std::thread([p] {
    guarded_callback("websocket I/O", [&] { p->server.run(); });
    p->io_done = true;  // the destructor stops waiting for closing handshakes
  });
  return std::unique_ptr<WsServer>(new WsServer(std::move(impl)));
}

WsServer::~WsServer() {
  websocketpp::lib::error_code ec;
  impl_->server.stop_listening(ec);
  std::vector<Handle> open;
  {
    std::lock_guard lock(impl_->mutex);
    for (const auto& [id, hdl] : impl_->handles) open.push_back(hdl);
  }
  for (const Handle& hdl : open)
    impl_->server.close(hdl, websocketpp::close::status::going_away, "bridge stopping", ec);
  // The I/O thread ends by itself once every closing handshake is done; a client that does not
  // answer within a second is cut off.
  for (int i = 0; i < 100 && !impl_->io_done; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  impl_->server.stop();
  if (impl_->io.joinable()) impl_->io.join();
}

std::vector<ClientEvent> WsServer::take_events() {
  std::lock_guard lock(impl_->mutex);
  std::vector<ClientEvent> out;
  out.swap(impl_->events);
  return out;
}

void WsServer::send_text(WsClientId client, const std::string& text) {
  impl_->send(client, text, websocketpp::frame::opcode::text, false);
}

void WsServer::send_binary(WsClientId client, const std::string& bytes) {
  impl_->send(client, bytes, websocketpp::frame::opcode::binary, true);
}

uint16_t WsServer::port() const {
  websocketpp::lib::asio::error_code ec;
  const auto endpoint = impl_->server.get_local_endpoint(ec);
  return ec ? 0 : endpoint.port();
}

}  // namespace slam::bridge
