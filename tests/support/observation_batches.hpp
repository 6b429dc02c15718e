#pragma once
// slam/robot/observations from a test's side: playing a gateway (each observation in a batch of
// its own) or reading the stream one observation at a time (each batch unpacked in order).
#include <atomic>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>

#include "common/fastdds/fast_topics.hpp"
#include "inbox.hpp"

namespace slam::testkit {

inline RobotObservationBatch batch_of(RobotObservation observation) {
  static std::atomic<std::uint64_t> next_seq{1};
  RobotObservationBatch batch;
  batch.gateway_id("test");
  batch.batch_seq(next_seq++);
  batch.observations().push_back(std::move(observation));
  return batch;
}

// A reader calling `on_observation(const RobotObservation&)` for every observation of every batch.
template <class F>
std::unique_ptr<dds::Reader<RobotObservationBatch>> make_observation_reader(dds::Participant& p,
                                                                            F on_observation) {
  auto r = dds::make_reader(p, dds::kRobotObservations,
                            [on_observation](const RobotObservationBatch& batch, const auto&) mutable {
                              for (const RobotObservation& o : batch.observations()) on_observation(o);
                            });
  if (!r) throw std::runtime_error(r.message());
  return std::move(*r);
}

// A reader whose observations go into `inbox`; the inbox must outlive the reader.
inline std::unique_ptr<dds::Reader<RobotObservationBatch>> make_observation_inbox_reader(
    dds::Participant& p, Inbox<RobotObservation>& inbox) {
  return make_observation_reader(p, [&inbox](const RobotObservation& o) { inbox.push(o); });
}

}  // namespace slam::testkit
