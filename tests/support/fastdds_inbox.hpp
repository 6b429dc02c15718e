#pragma once
// Fast DDS edge of the Inbox for tests that link slam_fastdds: a reader that feeds an Inbox, a
// writer, and a Requester (requests resent under their id until answered: no wait for a match),
// all throwing on set-up failure (the test fails with the message).
#include <memory>
#include <stdexcept>

#include "common/fastdds/dds.hpp"
#include "common/fastdds/requester.hpp"
#include "inbox.hpp"

namespace slam::testkit {

template <class T, class P>
std::unique_ptr<dds::Writer<T>> make_test_writer(dds::Participant& p, const dds::Topic<T, P>& topic) {
  auto w = dds::make_writer(p, topic);
  if (!w) throw std::runtime_error(w.message());
  return std::move(*w);
}

// A reader whose samples go into `inbox`; the inbox must outlive the reader.
template <class T, class P>
std::unique_ptr<dds::Reader<T>> make_inbox_reader(dds::Participant& p, const dds::Topic<T, P>& topic,
                                                  Inbox<T>& inbox) {
  auto r = dds::make_reader(p, topic, [&inbox](const T& s, const auto&) { inbox.push(s); });
  if (!r) throw std::runtime_error(r.message());
  return std::move(*r);
}

// A requester on `reply_topic` giving up after `timeout`.
template <class Rep, class P>
std::unique_ptr<dds::Requester<Rep>> make_test_requester(dds::Participant& p,
                                                         const dds::Topic<Rep, P>& reply_topic,
                                                         std::chrono::milliseconds timeout) {
  RetryPolicy policy;
  policy.timeout = timeout;
  auto r = dds::Requester<Rep>::create(p, reply_topic, policy);
  if (!r) throw std::runtime_error(r.message());
  return std::move(*r);
}

}  // namespace slam::testkit
