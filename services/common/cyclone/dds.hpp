#pragma once
// The Cyclone DDS edge shared by the simulator and the interop test: topics.hpp's QosSpec translated
// to a dds_qos_t (so Cyclone and the Fast DDS services always agree on QoS), entity ownership, and
// topic/writer creation that names the entity when it fails.
#include <dds/dds.h>

#include <cstddef>
#include <memory>
#include <string_view>

#include "common/core/result.hpp"
#include "common/core/topics.hpp"

namespace slam::cyclone {

struct QosDeleter {
  void operator()(dds_qos_t* q) const { dds_delete_qos(q); }
};
using QosPtr = std::unique_ptr<dds_qos_t, QosDeleter>;

QosPtr make_qos(const topics::QosSpec& spec);

// Deletes a Cyclone entity (participant, reader, writer...) when it goes out of scope.
class Entity {
 public:
  Entity() = default;
  explicit Entity(dds_entity_t e) : e_(e) {}
  ~Entity() {
    if (e_ > 0) dds_delete(e_);
  }
  Entity(Entity&& o) noexcept : e_(o.e_) { o.e_ = 0; }
  Entity& operator=(Entity&& o) noexcept {
    std::swap(e_, o.e_);
    return *this;
  }
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;
  dds_entity_t get() const { return e_; }
  bool ok() const { return e_ > 0; }

 private:
  dds_entity_t e_ = 0;
};

// The topic `info` (name and QoS from the table) of `type` on `participant`.
Result<dds_entity_t> make_topic(dds_entity_t participant, const dds_topic_descriptor_t* type,
                                const topics::TopicInfo& info);
// A writer of `info` (creating its topic) with the table's QoS.
Result<dds_entity_t> make_writer(dds_entity_t participant, const dds_topic_descriptor_t* type,
                                 const topics::TopicInfo& info);

// Copies `text` into a bounded IDL string (char[N], N including the terminator), cutting at a
// UTF-8 character boundary when it is too long.
void copy_bounded(std::string_view text, char* out, size_t capacity);

}  // namespace slam::cyclone
