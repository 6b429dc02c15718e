#pragma once
// The Cyclone DDS edge's view of topics.hpp: the same QosSpec translated to a dds_qos_t, so the
// simulator (Cyclone) and the Fast DDS services always agree on QoS.
#include <dds/dds.h>

#include <memory>

#include "common/topics.hpp"

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

}  // namespace slam::cyclone
