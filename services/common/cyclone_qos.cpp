#include "common/cyclone_qos.hpp"

namespace slam::cyclone {

QosPtr make_qos(const topics::QosSpec& spec) {
  QosPtr q(dds_create_qos());
  dds_qset_reliability(q.get(), spec.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT, DDS_MSECS(100));
  dds_qset_durability(q.get(), spec.transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, spec.depth);
  dds_qset_liveliness(q.get(), DDS_LIVELINESS_AUTOMATIC, spec.lease_ms > 0 ? DDS_MSECS(spec.lease_ms) : DDS_INFINITY);
  return q;
}

}  // namespace slam::cyclone
