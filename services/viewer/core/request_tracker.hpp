#pragma once
// The result of the last request a tab sent to a service that answers by request id (the MQTT
// gateway's MqttReply, the simulator's SimReply): waiting, ok, failed with the service's message,
// or no reply within the timeout. Replies to other requests (older ones, other viewers') are
// ignored: only the last request is shown.
#include <cstdint>
#include <optional>
#include <string>

namespace slam::viewer {

inline constexpr int64_t kReplyTimeoutNs = 3'000'000'000;  // a service answers within ms; 3 s is "none"

enum class RequestState : uint8_t { Waiting, Ok, Failed, NoReply };

struct RequestOutcome {
  uint64_t id = 0;
  std::string what;  // "spawn 2 robots", "publish 4 octets to v1/server/r1/cmd"
  RequestState state = RequestState::Waiting;
  std::string message;  // the service's reply text
  int64_t sent_ns = 0;
};

class RequestTracker {
 public:
  explicit RequestTracker(int64_t timeout_ns = kReplyTimeoutNs) : timeout_ns_(timeout_ns) {}

  // A request went out with `id` (non-zero); it becomes the last one, waiting for its reply.
  void sent(uint64_t id, std::string what, int64_t now_ns);
  // A reply arrived; true when it answers the last request (also after it was declared
  // unanswered: a late reply still tells what happened).
  bool reply(uint64_t id, bool ok, std::string message);
  // Declares the last request unanswered once it waited longer than the timeout.
  void tick(int64_t now_ns);

  const std::optional<RequestOutcome>& last() const { return last_; }

 private:
  int64_t timeout_ns_;
  std::optional<RequestOutcome> last_;
};

// "#12 spawn 2 robots: ok", "...: failed: unknown robot 'r9'", "...: waiting", "...: no reply".
std::string describe(const RequestOutcome& r);

}  // namespace slam::viewer
