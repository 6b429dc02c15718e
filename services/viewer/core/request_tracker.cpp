// Last-request matching and timeout (see request_tracker.hpp).
#include "viewer/core/request_tracker.hpp"

#include <utility>

namespace slam::viewer {

void RequestTracker::sent(uint64_t id, std::string what, int64_t now_ns) {
  last_ = RequestOutcome{id, std::move(what), RequestState::Waiting, {}, now_ns};
}

bool RequestTracker::reply(uint64_t id, bool ok, std::string message) {
  if (!last_ || id == 0 || last_->id != id) return false;
  last_->state = ok ? RequestState::Ok : RequestState::Failed;
  last_->message = std::move(message);
  return true;
}

void RequestTracker::tick(int64_t now_ns) {
  if (last_ && last_->state == RequestState::Waiting && now_ns - last_->sent_ns > timeout_ns_)
    last_->state = RequestState::NoReply;
}

std::string describe(const RequestOutcome& r) {
  // Appended piecewise: "#" + std::to_string(...) trips GCC 12's false -Wrestrict.
  std::string s = "#";
  s += std::to_string(r.id);
  s += " " + r.what + ": ";
  switch (r.state) {
    case RequestState::Waiting:
      return s + "waiting for the reply";
    case RequestState::Ok:
      return s + "ok" + (r.message.empty() ? "" : " (" + r.message + ")");
    case RequestState::Failed:
      return s + "failed: " + r.message;
    case RequestState::NoReply:
      return s + "no reply";
  }
  return s;
}

}  // namespace slam::viewer
