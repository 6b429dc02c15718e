#pragma once
// What every subcommand does with its Session: one-line errors, sending a sample to the service that
// serves a topic, request/reply with retries, and collecting the latest samples of a state topic.
#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
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

// Writes one sample to whoever serves `topic` (waits for a reader first, then for its ack).
template <class T, class P>
int send(Session& s, const dds::Topic<T, P>& topic, const T& sample, const char* served_by) {
  auto writer = dds::make_writer(s.participant(), topic);
  if (!writer) return fail(writer.message());
  if (!(*writer)->wait_for_readers(s.timeout()))
    return fail(std::string("no ") + served_by + " on DDS domain " + std::to_string(s.domain()) +
                " (is it running?)");
  if (!(*writer)->write(sample)) return fail(std::string("could not write to ") + topic.info.name);
  if (!(*writer)->wait_for_acknowledgments(s.timeout()))
    return fail(std::string(served_by) + " did not acknowledge the request");
  return 0;
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

}  // namespace slam::ctl
