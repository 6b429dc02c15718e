#pragma once
// Requests that cannot be lost, the Fast DDS side: a Requester reads one reply topic and sends
// requests through the caller's writers, each again under the same id on the RetrySchedule until
// its reply arrives or the deadline passes (core/request_retry.hpp). Nothing waits for a match:
// a copy sent before the responder or this reader was discovered is simply sent again, and the
// responder answers a repeat from its ReplyCache without executing it twice.
#include <algorithm>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include "common/core/request_retry.hpp"
#include "common/fastdds/dds.hpp"

namespace slam::dds {

// Requests and replies name their id request_id, except the simulator's (command_id).
template <class T>
uint64_t request_id_of(const T& sample) {
  if constexpr (requires { sample.command_id(); })
    return sample.command_id();
  else
    return sample.request_id();
}

template <class T>
void set_request_id(T& sample, uint64_t id) {
  if constexpr (requires { sample.command_id(id); })
    sample.command_id(id);
  else
    sample.request_id(id);
}

template <class Rep>
class Requester {
 public:
  // Runs once per request: with its reply, or with nothing when the deadline passed.
  using Done = std::function<void(const std::optional<Rep>&)>;
  // Sees every reply on the topic (also to other requesters' requests), on the reader's thread.
  using Listener = std::function<void(const Rep&)>;

  template <class P>
  static Result<std::unique_ptr<Requester>> create(Participant& participant, const Topic<Rep, P>& reply_topic,
                                                   RetryPolicy policy = {}, Listener listener = {}) {
    std::unique_ptr<Requester> r(new Requester(policy, std::move(listener)));
    auto reader = make_reader(participant, reply_topic,
                              [p = r.get()](const Rep& reply, const auto&) { p->on_reply(reply); });
    if (!reader) return reader.error();
    r->reader_ = std::move(*reader);
    r->thread_ = std::thread([p = r.get()] { p->resend_loop(); });
    return r;
  }

  ~Requester() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
    reader_.reset();
  }
  Requester(const Requester&) = delete;
  Requester& operator=(const Requester&) = delete;

  // Gives `request` a fresh id, writes it now and again until answered; returns the id. `writer`
  // must outlive this Requester. `done` runs on the reader's or the resend thread.
  template <class Req>
  uint64_t send(Writer<Req>& writer, Req request, Done done = {}) {
    const uint64_t id = ids_.next();
    set_request_id(request, id);
    RetrySchedule schedule(policy_, RetrySchedule::Clock::now());
    schedule.due(RetrySchedule::Clock::now());  // the first copy goes out below
    {
      std::lock_guard lock(mutex_);
      pending_.emplace(
          id, Pending{[&writer, request] { return writer.write(request); }, schedule, std::move(done)});
    }
    writer.write(request);
    wake_.notify_all();
    return id;
  }

  // Sends `request` and blocks until its reply, or nothing when the deadline passed.
  template <class Req>
  std::optional<Rep> call(Writer<Req>& writer, Req request) {
    std::mutex mutex;
    std::condition_variable answered;
    bool finished = false;
    std::optional<Rep> result;
    send(writer, std::move(request), [&](const std::optional<Rep>& reply) {
      std::lock_guard lock(mutex);
      result = reply;
      finished = true;
      answered.notify_all();
    });
    std::unique_lock lock(mutex);
    answered.wait(lock, [&] { return finished; });
    return result;
  }

  const RetryPolicy& policy() const { return policy_; }

 private:
  struct Pending {
    std::function<bool()> write;
    RetrySchedule schedule;
    Done done;
  };

  Requester(RetryPolicy policy, Listener listener) : policy_(policy), listener_(std::move(listener)) {}

  void on_reply(const Rep& reply) {
    if (listener_) listener_(reply);
    Done done;
    {
      std::lock_guard lock(mutex_);
      auto it = pending_.find(request_id_of(reply));
      if (it == pending_.end()) return;  // a repeat of a reply already taken, or another requester's
      done = std::move(it->second.done);
      pending_.erase(it);
    }
    if (done) done(reply);
  }

  // Resends what is due and gives up on what expired; the callbacks run outside the lock.
  void resend_loop() {
    std::vector<std::function<bool()>> resend;
    std::vector<Done> expired;
    std::unique_lock lock(mutex_);
    while (!stopping_) {
      auto next = RetrySchedule::Clock::now() + policy_.max_interval;
      const auto now = RetrySchedule::Clock::now();
      for (auto it = pending_.begin(); it != pending_.end();) {
        Pending& p = it->second;
        if (p.schedule.expired(now)) {
          expired.push_back(std::move(p.done));
          it = pending_.erase(it);
          continue;
        }
        if (p.schedule.due(now)) resend.push_back(p.write);
        next = std::min(next, p.schedule.next_send());
        ++it;
      }
      if (!resend.empty() || !expired.empty()) {
        lock.unlock();
        for (auto& write : resend) write();
        for (auto& done : expired)
          if (done) done(std::nullopt);
        resend.clear();
        expired.clear();
        lock.lock();
        continue;
      }
      wake_.wait_until(lock, next);
    }
  }

  RetryPolicy policy_;
  Listener listener_;
  RequestIdSource ids_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::map<uint64_t, Pending> pending_;
  std::unique_ptr<Reader<Rep>> reader_;
  std::thread thread_;  // last: started when everything it touches exists
};

}  // namespace slam::dds
