#pragma once
// What every subcommand does with its Session: one-line errors, sending a sample to the service that
// serves a topic, request/reply with retries, and collecting the latest samples of a state topic.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>

#include "common/core/service_options.hpp"
#include "common/core/shutdown.hpp"
#include "common/fastdds/requester.hpp"
#include "slamctl/commands.hpp"
#include "slamctl/format.hpp"

namespace slam::ctl {

using namespace std::chrono_literals;

inline int fail(const std::string& why) {
  report_error("slamctl", why);
  return kExitFailure;
}

inline int usage_error(const std::string& why) {
  report_error("slamctl", why);
  return kExitUsage;
}

inline Point2 point(double x, double y) {
  Point2 p;
  p.x(x);
  p.y(y);
  return p;
}

inline bool wait_until(const std::function<bool()>& pred, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!pred()) {
    if (std::chrono::steady_clock::now() >= until || shutdown_requested()) return false;
    std::this_thread::sleep_for(10ms);
  }
  return true;
}

// Sends a request and waits for the reply with the same request id, sending it again on the retry
// schedule until then (the responder answers a repeat without executing it twice): no wait for a
// match first, so a responder that starts after slamctl still answers within the timeout.
template <class Req, class ReqP, class Rep, class RepP>
std::optional<Rep> request(Session& s, const dds::Topic<Req, ReqP>& req_topic, const Req& req,
                           const dds::Topic<Rep, RepP>& rep_topic, const char* served_by) {
  auto writer = dds::make_writer(s.participant(), req_topic);
  if (!writer) {
    fail(writer.message());
    return std::nullopt;
  }
  RetryPolicy policy;
  policy.timeout = s.timeout();
  auto requester = dds::Requester<Rep>::create(s.participant(), rep_topic, policy);
  if (!requester) {
    fail(requester.message());
    return std::nullopt;
  }
  auto reply = (*requester)->call(**writer, req);
  if (!reply)
    fail(std::string("no reply from ") + served_by + " on DDS domain " + std::to_string(s.domain()) +
         " within " + std::to_string(s.timeout().count()) + " ms (is it running?)");
  return reply;
}

// Sends a request the mapper answers with a MapReply and prints one line: the reply's text, or
// `done` when the mapper said nothing more than ok. 0 on MAP_OK, else one error line and 1.
template <class Req, class ReqP>
int map_request(Session& s, const dds::Topic<Req, ReqP>& req_topic, const Req& req, const std::string& done) {
  const auto reply = request(s, req_topic, req, dds::kMapReply, "mapper");
  if (!reply) return kExitFailure;
  if (reply->result() != MAP_OK)
    return fail(map_result_name(reply->result()) + ": " + reply->message().to_string());
  std::printf("%s\n", reply->message().size() == 0 ? done.c_str() : reply->message().c_str());
  return 0;
}

// The latest sample per key of a state topic (and the first, for rates), collected on the
// reader's thread.
template <class T>
class Latest {
 public:
  template <class P, class Key>
  Latest(Session& s, const dds::Topic<T, P>& topic, Key key) {
    auto reader = dds::make_reader(s.participant(), topic, [this, key](const T& sample, const auto&) {
      std::lock_guard lock(mutex_);
      const std::string k = key(sample);
      first_.try_emplace(k, sample);
      latest_[k] = sample;
    });
    if (!reader) {
      fail(reader.message());
      return;
    }
    reader_ = std::move(*reader);
  }
  bool ok() const { return reader_ != nullptr; }
  bool matched() const { return reader_ && reader_->matched_writers() > 0; }
  bool heard() {
    std::lock_guard lock(mutex_);
    return !latest_.empty();
  }
  std::map<std::string, T> take() {
    reader_.reset();
    std::lock_guard lock(mutex_);
    return std::move(latest_);
  }
  // The first sample per key; call after take().
  std::map<std::string, T> take_first() {
    std::lock_guard lock(mutex_);
    return std::move(first_);
  }

 private:
  std::mutex mutex_;
  std::map<std::string, T> latest_;
  std::map<std::string, T> first_;
  std::unique_ptr<dds::Reader<T>> reader_;
};

// Listens for `listen` once `first` matched a writer and heard its first sample (nothing to hear
// when no writer matched within the timeout): discovery alone can take seconds, and on a loaded
// machine the samples kept for late joiners arrive seconds after the match.
template <class T>
void listen_after_match(Session& s, Latest<T>& first, std::chrono::milliseconds listen) {
  if (!wait_until([&] { return first.matched(); }, s.timeout())) return;
  if (wait_until([&] { return first.heard(); }, s.timeout())) wait_for_shutdown(listen);
}

// The running instances (not stopping) of the named services, from one round of heartbeats: every
// service beats at least once a second.
inline int running_instances(Session& s, std::initializer_list<std::string_view> services) {
  Latest<Heartbeat> beats(s, dds::kHeartbeat, [](const Heartbeat& h) { return h.instance_id().to_string(); });
  if (!beats.ok()) return 0;
  listen_after_match(s, beats, std::min<std::chrono::milliseconds>(s.timeout(), 1500ms));
  int count = 0;
  for (const auto& [id, hb] : beats.take()) {
    const bool serves =
        std::find(services.begin(), services.end(), hb.service().to_string()) != services.end();
    if (serves && hb.state() != SERVICE_STOPPING) ++count;
  }
  return count;
}

// Writes one sample to every running instance of the services in `served_by` and waits for their
// acknowledgements. The sample is volatile for whoever matches after the write, so the write waits
// until as many readers have matched as instances beat (at least one), not only the first; it
// fails, naming the count, when some did not match within the timeout. `reached`: the readers written to.
template <class T, class P>
int send(Session& s, const dds::Topic<T, P>& topic, const T& sample,
         std::initializer_list<std::string_view> served_by, int* reached = nullptr) {
  std::string names;
  for (const std::string_view name : served_by) names += (names.empty() ? "" : " or ") + std::string(name);
  auto writer = dds::make_writer(s.participant(), topic);
  if (!writer) return fail(writer.message());
  const int expected = std::max(1, running_instances(s, served_by));
  if (!wait_until([&] { return (*writer)->matched_readers() >= expected; }, s.timeout()) &&
      (*writer)->matched_readers() == 0)
    return fail("no " + names + " on DDS domain " + std::to_string(s.domain()) + " (is it running?)");
  const int matched = (*writer)->matched_readers();
  if (!(*writer)->write(sample)) return fail(std::string("could not write to ") + topic.info.name);
  if (!(*writer)->wait_for_acknowledgments(s.timeout()))
    return fail(names + " did not acknowledge the request");
  if (matched < expected)
    return fail("reached only " + std::to_string(matched) + " of " + std::to_string(expected) + " running " +
                names + " instances: run the command again");
  if (reached) *reached = matched;
  return 0;
}

}  // namespace slam::ctl
