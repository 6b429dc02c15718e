// bench_pipeline's Foxglove client (see pipeline_bridge_client.hpp).
#include "pipeline_bridge_client.hpp"

#include <atomic>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <websocketpp/client.hpp>
#include <websocketpp/config/asio_no_tls_client.hpp>

namespace slam::bench {

using Client = websocketpp::client<websocketpp::config::asio_client>;
using Handle = websocketpp::connection_hdl;

struct BridgeClient::Impl {
  Client client;
  std::thread io;
  Handle handle;
  mutable std::mutex mutex;  // guards totals (I/O thread vs the bench)
  Totals totals;
  uint32_t next_subscription = 1;

  // An advertise op: one subscription per channel, subscription id = its own counter.
  void on_text(const std::string& text) {
    const auto j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
    std::lock_guard lock(mutex);
    ++totals.text_frames;
    if (!j.is_object() || j.value("op", "") != "advertise" || !j.contains("channels")) return;
    auto subscriptions = nlohmann::json::array();
    for (const auto& channel : j["channels"]) {
      if (!channel.contains("id")) continue;
      subscriptions.push_back({{"id", next_subscription++}, {"channelId", channel["id"]}});
      ++totals.channels;
    }
    const nlohmann::json subscribe = {{"op", "subscribe"}, {"subscriptions", subscriptions}};
    websocketpp::lib::error_code ec;
    client.send(handle, subscribe.dump(), websocketpp::frame::opcode::text, ec);
  }
};

BridgeClient::BridgeClient(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

Result<std::unique_ptr<BridgeClient>> BridgeClient::connect(uint16_t port) {
  auto impl = std::make_unique<Impl>();
  Impl* p = impl.get();
  Client& c = p->client;
  c.clear_access_channels(websocketpp::log::alevel::all);
  c.clear_error_channels(websocketpp::log::elevel::all);
  websocketpp::lib::error_code ec;
  c.init_asio(ec);
  if (ec) return Error{"bridge client: " + ec.message()};
  c.set_open_handler([p](Handle) {
    std::lock_guard lock(p->mutex);
    p->totals.open = true;
  });
  const auto closed = [p](Handle) {
    std::lock_guard lock(p->mutex);
    p->totals.open = false;
  };
  c.set_close_handler(closed);
  c.set_fail_handler(closed);
  c.set_message_handler([p](Handle, Client::message_ptr msg) {
    if (msg->get_opcode() == websocketpp::frame::opcode::text) return p->on_text(msg->get_payload());
    std::lock_guard lock(p->mutex);
    ++p->totals.messages;
    p->totals.bytes += msg->get_payload().size();
  });
  auto con = c.get_connection("ws://127.0.0.1:" + std::to_string(port), ec);
  if (ec) return Error{"bridge client: " + ec.message()};
  con->add_subprotocol("foxglove.websocket.v1", ec);
  if (ec) return Error{"bridge client: " + ec.message()};
  p->handle = con->get_handle();
  c.connect(con);
  p->io = std::thread([p] { p->client.run(); });
  return std::unique_ptr<BridgeClient>(new BridgeClient(std::move(impl)));
}

BridgeClient::~BridgeClient() {
  websocketpp::lib::error_code ec;
  impl_->client.close(impl_->handle, websocketpp::close::status::going_away, "bench done", ec);
  impl_->client.stop();
  if (impl_->io.joinable()) impl_->io.join();
}

BridgeClient::Totals BridgeClient::totals() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->totals;
}

bool BridgeClient::wait_subscribed(uint32_t channels, std::chrono::milliseconds timeout) const {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until) {
    const Totals t = totals();
    if (t.channels >= channels) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

}  // namespace slam::bench
