#pragma once
// The Fast DDS edge every server service uses: a participant, and typed writers and readers whose
// QoS comes only from topics.hpp. Every return code is checked; no exception leaves a listener.
#include <chrono>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "common/core/guarded_callback.hpp"
#include "common/core/result.hpp"
#include "common/core/topics.hpp"
#include "common/fastdds/security_files.hpp"

namespace slam::dds {

namespace fdds = eprosima::fastdds::dds;

// A topic name bound to its generated type (T) and type support (PubSubT).
template <class T, class PubSubT>
struct Topic {
  topics::TopicInfo info;
};

fdds::DataWriterQos writer_qos(const topics::QosSpec& spec);
fdds::DataReaderQos reader_qos(const topics::QosSpec& spec);

// One DomainParticipant with one publisher and one subscriber. Transports: UDPv4 only, so a killed
// process leaves no shared-memory files behind; when FASTRTPS_DEFAULT_PROFILES_FILE is set, the XML
// profile decides instead (multi-host set-ups, discovery server; see docs/deployment.md).
// With security files the participant joins a DDS Security domain (authenticated, access-controlled,
// encrypted: docs/security.md) after check_security_files() passed; an error names the bad file.
class Participant {
 public:
  // Security from the environment (SLAM_DDS_SECURITY_DIR, SLAM_DDS_IDENTITY): every program's way.
  static Result<std::unique_ptr<Participant>> create(int domain_id, const std::string& name);
  static Result<std::unique_ptr<Participant>> create(int domain_id, const std::string& name,
                                                     const std::optional<SecurityFiles>& security);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  int domain_id() const { return domain_id_; }
  fdds::Publisher* publisher() { return publisher_; }
  fdds::Subscriber* subscriber() { return subscriber_; }

  // The topic called `name` of type PubSubT, created on first use.
  template <class PubSubT>
  Result<fdds::Topic*> topic(const char* name) {
    return topic_impl(name, [] { return fdds::TypeSupport(new PubSubT()); });
  }

 private:
  Participant() = default;
  Result<fdds::Topic*> topic_impl(const char* name, const std::function<fdds::TypeSupport()>& make_type);

  int domain_id_ = 0;
  fdds::DomainParticipant* participant_ = nullptr;
  fdds::Publisher* publisher_ = nullptr;
  fdds::Subscriber* subscriber_ = nullptr;
  std::mutex mutex_;
  std::map<std::string, fdds::Topic*> topics_;
};

// True when rc is OK; otherwise logs (rate-limited) the topic and the code.
bool log_write_result(const eprosima::fastrtps::types::ReturnCode_t& rc, fdds::DataWriter* writer);
int matched_subscriptions(fdds::DataWriter* writer);
bool acknowledged(fdds::DataWriter* writer, std::chrono::milliseconds timeout);
int matched_publications(fdds::DataReader* reader);

inline constexpr std::chrono::milliseconds kMatchSettle{300};

// Polls `matched` until it reaches n (false after timeout), then waits kMatchSettle: a match is
// seen on one side first, and the other endpoint may match a moment later.
bool wait_matched(const std::function<int()>& matched, int n, std::chrono::milliseconds timeout);

// Writes samples of T. write() returns false when the middleware refused the sample
// (logged rate-limited); callers count it.
template <class T>
class Writer {
 public:
  Writer(fdds::Publisher* publisher, fdds::DataWriter* writer) : publisher_(publisher), writer_(writer) {}
  ~Writer() { publisher_->delete_datawriter(writer_); }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Fast DDS's write() takes a non-const pointer but does not modify the sample. The overload with
  // a handle returns a ReturnCode_t (the one without returns bool).
  bool write(const T& sample) {
    return log_write_result(writer_->write(const_cast<T*>(&sample), fdds::HANDLE_NIL), writer_);
  }
  // The instance keyed like `key_sample` is gone (a forgotten robot): readers and late joiners of a
  // transient-local topic no longer get its last sample from this writer.
  bool dispose(const T& key_sample) {
    return log_write_result(writer_->dispose(const_cast<T*>(&key_sample), fdds::HANDLE_NIL), writer_);
  }
  // This writer no longer speaks for the instance (another instance of the service took it over);
  // its last sample is not replayed to late joiners.
  bool unregister(const T& key_sample) {
    return log_write_result(writer_->unregister_instance(const_cast<T*>(&key_sample), fdds::HANDLE_NIL),
                            writer_);
  }
  // Number of readers currently matched (for readiness checks and tests).
  int matched_readers() const;
  // Waits until `n` readers matched, then a little longer: the remote reader may match this writer
  // a moment after this writer matched it, and a volatile reader drops samples that arrive before.
  // Short-lived senders (slamctl, tests) call this before their first write.
  bool wait_for_readers(std::chrono::milliseconds timeout, int n = 1) {
    return wait_matched([this] { return matched_readers(); }, n, timeout);
  }
  // Blocks until every matched reader acknowledged what was written (reliable topics), or timeout.
  bool wait_for_acknowledgments(std::chrono::milliseconds timeout) { return acknowledged(writer_, timeout); }
  std::string topic_name() const { return writer_->get_topic()->get_name(); }

 private:
  fdds::Publisher* publisher_;
  fdds::DataWriter* writer_;
};

template <class T>
int Writer<T>::matched_readers() const {
  return matched_subscriptions(writer_);
}

// Reads samples of T. With a callback, each valid sample is handed to it on the middleware's
// listener thread (keep it short, and never touch GL or block there); without one, call take().
template <class T>
class Reader : private fdds::DataReaderListener {
 public:
  using Callback = std::function<void(const T&, const fdds::SampleInfo&)>;

  Reader(fdds::Subscriber* subscriber, Callback cb) : subscriber_(subscriber), callback_(std::move(cb)) {}
  ~Reader() override {
    if (reader_) {
      reader_->set_listener(nullptr);
      subscriber_->delete_datareader(reader_);
    }
  }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  // Takes up to `max` valid samples into `out` (appended). Returns how many.
  size_t take(std::vector<T>& out, size_t max = SIZE_MAX) {
    size_t n = 0;
    fdds::SampleInfo info;
    while (n < max && reader_->take_next_sample(&scratch_, &info) ==
                          eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      out.push_back(scratch_);
      ++n;
    }
    return n;
  }
  int matched_writers() const { return matched_publications(reader_); }
  // Waits until `n` writers matched this reader, then a little longer: the remote writer may match
  // this reader a moment later, and a volatile writer sends nothing to a reader it has not matched.
  // Requesters (slamctl, tests) call this on their reply reader before sending a request.
  bool wait_for_writers(std::chrono::milliseconds timeout, int n = 1) {
    return wait_matched([this] { return matched_writers(); }, n, timeout);
  }
  // Samples the middleware knows this reader never got (DDS SAMPLE_LOST, cumulative): e.g. a
  // reliable writer's keep-last history replaced them before they were delivered.
  int64_t samples_lost() const {
    fdds::SampleLostStatus status;
    return reader_->get_sample_lost_status(status) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK
               ? status.total_count
               : 0;
  }
  fdds::DataReaderListener* listener() { return callback_ ? this : nullptr; }
  void attach(fdds::DataReader* reader) { reader_ = reader; }

 private:
  void on_data_available(fdds::DataReader* reader) override {
    guarded_callback("DDS reader", [&] {
      fdds::SampleInfo info;
      while (reader->take_next_sample(&scratch_, &info) ==
             eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
        if (info.valid_data) callback_(scratch_, info);
      }
    });
  }

  fdds::Subscriber* subscriber_;
  fdds::DataReader* reader_ = nullptr;
  Callback callback_;
  T scratch_{};  // reused for every sample: sequences keep their capacity
};

Result<fdds::DataWriter*> create_datawriter(fdds::Publisher* publisher, fdds::Topic* topic,
                                            const topics::QosSpec& qos);
Result<fdds::DataReader*> create_datareader(fdds::Subscriber* subscriber, fdds::Topic* topic,
                                            const topics::QosSpec& qos, fdds::DataReaderListener* listener);

template <class T, class PubSubT>
Result<std::unique_ptr<Writer<T>>> make_writer(Participant& p, const Topic<T, PubSubT>& t) {
  auto topic = p.template topic<PubSubT>(t.info.name);
  if (!topic) return topic.error();
  auto w = create_datawriter(p.publisher(), *topic, t.info.qos);
  if (!w) return w.error();
  return std::make_unique<Writer<T>>(p.publisher(), *w);
}

template <class T, class PubSubT>
Result<std::unique_ptr<Reader<T>>> make_reader(Participant& p, const Topic<T, PubSubT>& t,
                                               typename Reader<T>::Callback cb = {}) {
  auto topic = p.template topic<PubSubT>(t.info.name);
  if (!topic) return topic.error();
  auto reader = std::make_unique<Reader<T>>(p.subscriber(), std::move(cb));
  auto r = create_datareader(p.subscriber(), *topic, t.info.qos, reader->listener());
  if (!r) return r.error();
  reader->attach(*r);
  return reader;
}

}  // namespace slam::dds
