#include "common/fastdds/dds.hpp"

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <functional>
#include <thread>

#include "common/core/log.hpp"

namespace slam::dds {
namespace {

using eprosima::fastrtps::types::ReturnCode_t;

RateLimitedLog g_write_errors;

template <class Qos>
void apply(const topics::QosSpec& spec, Qos& q) {
  q.reliability().kind = spec.reliable ? fdds::RELIABLE_RELIABILITY_QOS : fdds::BEST_EFFORT_RELIABILITY_QOS;
  q.durability().kind =
      spec.transient_local ? fdds::TRANSIENT_LOCAL_DURABILITY_QOS : fdds::VOLATILE_DURABILITY_QOS;
  q.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
  q.history().depth = spec.depth;
  // Fast DDS defaults to 10 instances: a fleet has hundreds of robots (keys). Unlimited instances
  // and samples; keep-last bounds each instance to `depth`.
  q.resource_limits().max_instances = 0;
  q.resource_limits().max_samples = 0;
  q.resource_limits().max_samples_per_instance = spec.depth;
  q.liveliness().kind = fdds::AUTOMATIC_LIVELINESS_QOS;
  if (spec.lease_ms > 0) {
    q.liveliness().lease_duration = eprosima::fastrtps::Duration_t(
        spec.lease_ms / 1000, static_cast<uint32_t>((spec.lease_ms % 1000) * 1000000));
    q.liveliness().announcement_period = eprosima::fastrtps::Duration_t(spec.lease_ms / 3000.0);
  }
}

std::string code_name(const ReturnCode_t& rc) {
  switch (rc()) {
    case ReturnCode_t::RETCODE_OK:
      return "OK";
    case ReturnCode_t::RETCODE_TIMEOUT:
      return "TIMEOUT";
    case ReturnCode_t::RETCODE_OUT_OF_RESOURCES:
      return "OUT_OF_RESOURCES";
    case ReturnCode_t::RETCODE_NOT_ENABLED:
      return "NOT_ENABLED";
    case ReturnCode_t::RETCODE_BAD_PARAMETER:
      return "BAD_PARAMETER";
    case ReturnCode_t::RETCODE_PRECONDITION_NOT_MET:
      return "PRECONDITION_NOT_MET";
    default:
      return "error " + std::to_string(rc());
  }
}

// The builtin plugins of the DDS Security specification, on the files compose/make-security.sh makes.
void add_security(fdds::DomainParticipantQos& pqos, const SecurityFiles& files) {
  auto& properties = pqos.properties().properties();
  const auto add = [&](const std::string& name, const std::string& value) {
    properties.emplace_back(name, value);
  };
  const std::string auth = "dds.sec.auth.builtin.PKI-DH.";
  const std::string access = "dds.sec.access.builtin.Access-Permissions.";
  add("dds.sec.auth.plugin", "builtin.PKI-DH");
  add(auth + "identity_ca", "file://" + files.identity_ca);
  add(auth + "identity_certificate", "file://" + files.identity_certificate);
  add(auth + "private_key", "file://" + files.private_key);
  add("dds.sec.access.plugin", "builtin.Access-Permissions");
  add(access + "permissions_ca", "file://" + files.permissions_ca);
  add(access + "governance", "file://" + files.governance);
  add(access + "permissions", "file://" + files.permissions);
  add("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

// Payload encryption of a writer on a secure domain (without DDS Security nothing reads these):
// AES-128-GCM instead of Fast DDS's default AES-256-GCM (the same standard mode, 10 rounds instead
// of 14 on every sample), and a new session key every 1024 samples instead of every 32 (each is an
// HMAC-SHA256 derivation in the writer; with a random 64-bit nonce part, 1024 samples under one key
// leave a nonce repeat at about 2^-45). Measured in docs/performance.md#security.
void set_payload_crypto(fdds::PropertyPolicyQos& properties) {
  properties.properties().emplace_back("dds.sec.crypto.keysize", "128");
  properties.properties().emplace_back("dds.sec.crypto.maxblockspersession", "1024");
}

}  // namespace

fdds::DataWriterQos writer_qos(const topics::QosSpec& spec) {
  fdds::DataWriterQos q = fdds::DATAWRITER_QOS_DEFAULT;
  apply(spec, q);
  set_payload_crypto(q.properties());
  // Data sharing (on by default for fixed-size types) keeps files in /dev/shm that a killed
  // process leaves behind, like the shared-memory transport we also keep off.
  q.data_sharing().off();
  // Large samples (map snapshots) must be fragmented and may need resending; keep memory growable.
  q.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  if (spec.reliable) {
    q.reliability().max_blocking_time = eprosima::fastrtps::Duration_t(0, 100000000);
    // A volatile reliable writer frees a sample only once every reader has acknowledged it, and
    // readers acknowledge when a heartbeat asks. With the default 3 s heartbeat a 10 kHz stream
    // piles up ~30 000 samples, and Fast DDS searches its history linearly on every removal.
    q.reliable_writer_qos().times.heartbeatPeriod = eprosima::fastrtps::Duration_t(0, 100000000);
  }
  return q;
}

fdds::DataReaderQos reader_qos(const topics::QosSpec& spec) {
  fdds::DataReaderQos q = fdds::DATAREADER_QOS_DEFAULT;
  topics::QosSpec reader = spec;
  if (spec.reader_depth > 0) reader.depth = spec.reader_depth;
  apply(reader, q);
  q.data_sharing().off();
  q.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  return q;
}

Result<std::unique_ptr<Participant>> Participant::create(int domain_id, const std::string& name) {
  auto security = security_from_environment();
  if (!security) return security.error();
  return create(domain_id, name, *security);
}

Result<std::unique_ptr<Participant>> Participant::create(int domain_id, const std::string& name,
                                                         const std::optional<SecurityFiles>& security) {
  if (domain_id < 0 || domain_id > 232)
    return Error{"DDS domain id must be 0..232, got " + std::to_string(domain_id)};
  if (security) {
    if (Status s = check_security_files(*security); !s) return Error{"DDS security: " + s.message()};
  }
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  fdds::DomainParticipantQos pqos = factory->get_default_participant_qos();
  pqos.name(name);
  if (std::getenv("FASTRTPS_DEFAULT_PROFILES_FILE") == nullptr) {
    pqos.transport().use_builtin_transports = false;
    auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
    // Linux's default 208 KB socket buffers overflow on bursts of small samples (a fleet's
    // observations), and reliable retransmission then stalls the stream.
    udp->receiveBufferSize = 4 * 1024 * 1024;
    udp->sendBufferSize = 4 * 1024 * 1024;
    pqos.transport().user_transports.push_back(udp);
    // A restarted service must be matched again within the 3 s the system promises. When its first
    // multicast announcements are missed, peers only learn of it from the periodic one (3 s by
    // default): announce every second instead (one small packet per participant).
    pqos.wire_protocol().builtin.discovery_config.leaseDuration_announcementperiod =
        eprosima::fastrtps::Duration_t(1, 0);
  }
  if (security) add_security(pqos, *security);
  std::unique_ptr<Participant> p(new Participant());
  p->domain_id_ = domain_id;
  p->participant_ = factory->create_participant(static_cast<fdds::DomainId_t>(domain_id), pqos);
  if (!p->participant_) {
    return Error{"cannot create DDS participant on domain " + std::to_string(domain_id) +
                 (security ? " (DDS Security refused the files: see the lines above)" : "")};
  }
  p->publisher_ = p->participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  p->subscriber_ = p->participant_->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  if (!p->publisher_ || !p->subscriber_) return Error{"cannot create DDS publisher/subscriber"};
  return p;
}

Participant::~Participant() {
  if (!participant_) return;
  // Writers and readers are owned by their Writer/Reader objects, which must be gone by now.
  const ReturnCode_t rc = participant_->delete_contained_entities();
  if (rc != ReturnCode_t::RETCODE_OK) spdlog::warn("dds: deleting entities failed: {}", code_name(rc));
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

Result<fdds::Topic*> Participant::topic_impl(const char* name,
                                             const std::function<fdds::TypeSupport()>& make_type) {
  std::lock_guard lock(mutex_);
  if (auto it = topics_.find(name); it != topics_.end()) return it->second;
  fdds::TypeSupport type = make_type();
  const ReturnCode_t rc = type.register_type(participant_);
  if (rc != ReturnCode_t::RETCODE_OK && rc != ReturnCode_t::RETCODE_PRECONDITION_NOT_MET)
    return Error{"cannot register DDS type " + type.get_type_name() + ": " + code_name(rc)};
  fdds::Topic* topic = participant_->create_topic(name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  if (!topic) return Error{std::string("cannot create DDS topic ") + name};
  topics_.emplace(name, topic);
  return topic;
}

Result<fdds::DataWriter*> create_datawriter(fdds::Publisher* publisher, fdds::Topic* topic,
                                            const topics::QosSpec& qos) {
  fdds::DataWriter* w = publisher->create_datawriter(topic, writer_qos(qos));
  if (!w) return Error{"cannot create DDS writer for " + topic->get_name()};
  return w;
}

Result<fdds::DataReader*> create_datareader(fdds::Subscriber* subscriber, fdds::Topic* topic,
                                            const topics::QosSpec& qos, fdds::DataReaderListener* listener) {
  fdds::DataReader* r =
      subscriber->create_datareader(topic, reader_qos(qos), listener,
                                    listener ? fdds::StatusMask::data_available() : fdds::StatusMask::none());
  if (!r) return Error{"cannot create DDS reader for " + topic->get_name()};
  return r;
}

bool log_write_result(const ReturnCode_t& rc, fdds::DataWriter* writer) {
  if (rc == ReturnCode_t::RETCODE_OK) return true;
  const std::string topic = writer->get_topic()->get_name();
  g_write_errors.warn(topic, "dds: write on {} failed: {}", topic, code_name(rc));
  return false;
}

// get_matched_subscriptions()/get_matched_publications() are unsupported in Fast DDS 2.9; the
// matched statuses are.
int matched_subscriptions(fdds::DataWriter* writer) {
  fdds::PublicationMatchedStatus status;
  if (writer->get_publication_matched_status(status) != ReturnCode_t::RETCODE_OK) return 0;
  return status.current_count;
}

bool acknowledged(fdds::DataWriter* writer, std::chrono::milliseconds timeout) {
  const auto ms = timeout.count();
  const eprosima::fastrtps::Duration_t wait(static_cast<int32_t>(ms / 1000),
                                            static_cast<uint32_t>((ms % 1000) * 1000000));
  return writer->wait_for_acknowledgments(wait) == ReturnCode_t::RETCODE_OK;
}

int matched_publications(fdds::DataReader* reader) {
  fdds::SubscriptionMatchedStatus status;
  if (reader->get_subscription_matched_status(status) != ReturnCode_t::RETCODE_OK) return 0;
  return status.current_count;
}

bool wait_matched(const std::function<int()>& matched, int n, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (matched() < n) {
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(kMatchSettle);
  return true;
}

}  // namespace slam::dds
