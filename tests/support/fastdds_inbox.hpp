#pragma once
// Fast DDS edge of the Inbox for tests that link slam_fastdds: a reader that feeds an Inbox, and a
// writer, both throwing on set-up failure (the test fails with the message).
#include <memory>
#include <stdexcept>

#include "common/fastdds/dds.hpp"
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

}  // namespace slam::testkit
