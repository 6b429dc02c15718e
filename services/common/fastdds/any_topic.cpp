#include "common/fastdds/any_topic.hpp"

namespace slam::dds {
namespace {

template <class T, class PubSubT>
class TypedCdrWriter final : public CdrWriter {
 public:
  explicit TypedCdrWriter(std::unique_ptr<Writer<T>> writer) : writer_(std::move(writer)) {}
  Status write(std::span<const uint8_t> cdr) override {
    if (!from_cdr<PubSubT>(cdr, scratch_))
      return Error{"bytes that are not a " + std::string(PubSubT().getName()) + " for " +
                   writer_->topic_name()};
    if (!writer_->write(scratch_)) return Error{"could not write to " + writer_->topic_name()};
    return {};
  }
  int matched_readers() const override { return writer_->matched_readers(); }
  bool wait_for_acknowledgments(std::chrono::milliseconds timeout) override {
    return writer_->wait_for_acknowledgments(timeout);
  }

 private:
  std::unique_ptr<Writer<T>> writer_;
  T scratch_{};
};

template <class T>
class TypedCdrReader final : public CdrReader {
 public:
  explicit TypedCdrReader(std::unique_ptr<Reader<T>> reader) : reader_(std::move(reader)) {}
  int matched_writers() const override { return reader_->matched_writers(); }

 private:
  std::unique_ptr<Reader<T>> reader_;
};

template <class T, class PubSubT>
AnyTopic any(const Topic<T, PubSubT>& topic) {
  AnyTopic a;
  a.info = topic.info;
  a.type_name = PubSubT().getName();
  a.make_reader = [topic](Participant& p, CdrCallback cb) -> Result<std::unique_ptr<CdrReader>> {
    auto reader = make_reader(p, topic, [cb = std::move(cb)](const T& sample, const fdds::SampleInfo& info) {
      const std::vector<uint8_t> cdr = to_cdr<PubSubT>(sample);
      if (!cdr.empty()) cb(cdr, info);
    });
    if (!reader) return reader.error();
    return std::unique_ptr<CdrReader>(new TypedCdrReader<T>(std::move(*reader)));
  };
  a.make_writer = [topic](Participant& p) -> Result<std::unique_ptr<CdrWriter>> {
    auto writer = make_writer(p, topic);
    if (!writer) return writer.error();
    return std::unique_ptr<CdrWriter>(new TypedCdrWriter<T, PubSubT>(std::move(*writer)));
  };
  return a;
}

}  // namespace

const std::vector<AnyTopic>& all_topics() {
  // One topic a line (clang-format would pack them in columns: every new topic would move them all).
  // clang-format off
  static const std::vector<AnyTopic> table{
      any(kRobotObservations),
      any(kRobotState),
      any(kRobotOdometry),
      any(kPoseCorrection),
      any(kInitialPose),
      any(kPlacementAnswer),
      any(kGridSnapshot),
      any(kGridTiles),
      any(kGridConfig),
      any(kMapEdit),
      any(kMapFileRequest),
      any(kMapReply),
      any(kNavGoal),
      any(kRobotPath),
      any(kWaypointCommand),
      any(kPathRequest),
      any(kPathReply),
      any(kMqttTraffic),
      any(kMqttRequest),
      any(kMqttReply),
      any(kMqttSubscriptions),
      any(kSimControl),
      any(kSimReply),
      any(kSimWorld),
      any(kSimGroundTruth),
      any(kHeartbeat),
      any(kAlert),
      any(kForgetRobot),
      any(kNavMission),
      any(kRosMap),
      any(kRosTf),
      any(kRosGoalPose),
      any(kRosInitialPose),
      any(kFleetDigest),
      any(kFleetPoints),
  };
  // clang-format on
  return table;
}

const AnyTopic* find_topic(std::string_view name) {
  for (const AnyTopic& t : all_topics())
    if (name == t.info.name) return &t;
  return nullptr;
}

}  // namespace slam::dds
