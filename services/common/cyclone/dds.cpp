#include "common/cyclone/dds.hpp"

#include <fmt/format.h>

#include <cstring>

#include "common/core/bounded_text.hpp"

namespace slam::cyclone {

QosPtr make_qos(const topics::QosSpec& spec) {
  QosPtr q(dds_create_qos());
  dds_qset_reliability(q.get(), spec.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_MSECS(100));
  dds_qset_durability(q.get(),
                      spec.transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, spec.depth);
  dds_qset_liveliness(q.get(), DDS_LIVELINESS_AUTOMATIC,
                      spec.lease_ms > 0 ? DDS_MSECS(spec.lease_ms) : DDS_INFINITY);
  return q;
}

Result<dds_entity_t> make_topic(dds_entity_t participant, const dds_topic_descriptor_t* type,
                                const topics::TopicInfo& info) {
  const auto qos = make_qos(info.qos);
  const dds_entity_t t = dds_create_topic(participant, type, info.name, qos.get(), nullptr);
  if (t < 0) return Error{fmt::format("Cyclone topic {}: {}", info.name, dds_strretcode(t))};
  return t;
}

Result<dds_entity_t> make_writer(dds_entity_t participant, const dds_topic_descriptor_t* type,
                                 const topics::TopicInfo& info) {
  auto topic = make_topic(participant, type, info);
  if (!topic) return topic.error();
  const auto qos = make_qos(info.qos);
  const dds_entity_t w = dds_create_writer(participant, *topic, qos.get(), nullptr);
  if (w < 0) return Error{fmt::format("Cyclone writer {}: {}", info.name, dds_strretcode(w))};
  return w;
}

void copy_bounded(std::string_view text, char* out, size_t capacity) {
  const std::string_view cut = bounded_prefix(text, capacity - 1);
  std::memcpy(out, cut.data(), cut.size());
  out[cut.size()] = '\0';
}

}  // namespace slam::cyclone
