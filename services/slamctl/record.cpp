// The DDS edge of `slamctl record` and `slamctl replay` (the file side is recording.hpp).
#include "slamctl/record.hpp"

#include <unistd.h>

#include <cstdio>
#include <thread>

#include "common/core/clock.hpp"
#include "common/core/service_options.hpp"
#include "common/core/shutdown.hpp"
#include "common/fastdds/any_topic.hpp"
#include "slamctl/recording.hpp"
#include "slamctl/session_io.hpp"

namespace slam::ctl {
namespace {

std::vector<std::string> system_topics() {
  std::vector<std::string> names;
  for (const dds::AnyTopic& t : dds::all_topics()) names.emplace_back(t.info.name);
  return names;
}

std::string megabytes(uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f MB", static_cast<double>(bytes) / 1e6);
  return buf;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

uint64_t nanoseconds(const eprosima::fastrtps::rtps::Time_t& t) {
  return t.seconds() < 0 ? 0 : static_cast<uint64_t>(t.seconds()) * 1'000'000'000ULL + t.nanosec();
}

struct RecordArgs {
  std::string file;
  double duration_s = 0;
  std::string topics;  // comma-separated
};

int cmd_record(Session& s, const RecordArgs& a) {
  auto selected = select_topics(a.topics, system_topics());
  if (!selected) return usage_error(selected.message());
  auto recorder = SessionRecorder::create(a.file);
  if (!recorder) return fail(recorder.message());
  SessionRecorder& rec = **recorder;

  std::vector<std::unique_ptr<dds::CdrReader>> readers;
  for (const std::string& name : *selected) {
    const dds::AnyTopic& topic = *dds::find_topic(name);
    auto reader = topic.make_reader(
        s.participant(), [&rec, &topic](std::span<const uint8_t> cdr, const dds::fdds::SampleInfo& info) {
          rec.add(topic.info.name, topic.type_name, cdr, static_cast<uint64_t>(now_ns()),
                  nanoseconds(info.source_timestamp));
        });
    if (!reader) return fail(reader.message());
    readers.push_back(std::move(*reader));
  }

  // A progress line a second: rewritten in place on a terminal, one line per 10 s in a log.
  const bool tty = ::isatty(STDOUT_FILENO) != 0;
  const auto start = std::chrono::steady_clock::now();
  const auto until = start + std::chrono::duration<double>(a.duration_s > 0 ? a.duration_s : 1e12);
  int ticks = 0;
  while (!shutdown_requested() && !rec.failed() && std::chrono::steady_clock::now() < until) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now());
    wait_for_shutdown(std::min<std::chrono::milliseconds>(1000ms, std::max(left, 1ms)));
    if (!tty && ++ticks % 10 != 0) continue;
    const RecordingStats now = rec.stats();
    std::printf("%srecording %s: %llu messages on %zu topics, %s, %.0f s%s", tty ? "\r" : "", a.file.c_str(),
                static_cast<unsigned long long>(now.messages), now.topics, megabytes(now.bytes).c_str(),
                seconds_since(start), tty ? "   " : "\n");
    std::fflush(stdout);
  }
  readers.clear();  // no sample arrives while the file is closed
  if (tty) std::printf("\n");
  const RecordingStats done = rec.stats();
  if (Status closed = rec.close(); !closed) return fail(closed.message());
  std::printf("recorded %llu messages on %zu topics in %.1f s to %s (%s)\n",
              static_cast<unsigned long long>(done.messages), done.topics, seconds_since(start),
              a.file.c_str(), megabytes(done.bytes).c_str());
  return 0;
}

struct ReplayArgs {
  std::string file;
  double rate = 1.0;
  std::string topics;  // comma-separated
};

int cmd_replay(Session& s, const ReplayArgs& a) {
  auto selected = select_topics(a.topics, system_topics());
  if (!selected) return usage_error(selected.message());
  auto file = mcap::MappedFile::open(a.file);
  if (!file) return fail(file.message());
  auto recording = mcap::parse((*file)->bytes());
  if (!recording) return fail(a.file + ": " + recording.message());

  std::map<std::string, std::string> type_of;
  for (const dds::AnyTopic& t : dds::all_topics()) type_of.emplace(t.info.name, t.type_name);
  const ReplayPlan plan =
      plan_replay(*recording, type_of, a.topics.empty() ? std::vector<std::string>{} : *selected);
  for (const std::string& line : plan.skipped) std::printf("%s\n", line.c_str());

  std::map<uint16_t, std::unique_ptr<dds::CdrWriter>> writer_of;  // channel id -> writer
  for (const auto& [channel, topic] : plan.topic_of) {
    auto writer = dds::find_topic(topic)->make_writer(s.participant());
    if (!writer) return fail(writer.message());
    writer_of.emplace(channel, std::move(*writer));
  }
  // Give discovery up to the timeout to find a subscriber: volatile readers miss what is written
  // before they matched.
  if (!writer_of.empty())
    dds::wait_matched(
        [&] {
          int matched = 0;
          for (const auto& [channel, writer] : writer_of) matched += writer->matched_readers();
          return matched;
        },
        1, s.timeout());

  uint64_t first_log_time = UINT64_MAX;
  for (const mcap::MessageView& m : recording->messages)
    if (writer_of.contains(m.channel_id)) first_log_time = std::min(first_log_time, m.log_time);

  const auto start = std::chrono::steady_clock::now();
  uint64_t sent = 0, refused = 0;
  std::string first_refusal;
  for (const mcap::MessageView& m : recording->messages) {
    auto writer = writer_of.find(m.channel_id);
    if (writer == writer_of.end()) continue;
    const auto due = start + replay_offset(first_log_time, m.log_time, a.rate);
    while (!shutdown_requested() && std::chrono::steady_clock::now() < due)
      std::this_thread::sleep_until(std::min(due, std::chrono::steady_clock::now() + 100ms));
    if (shutdown_requested()) break;
    if (Status st = writer->second->write(m.data); !st) {
      if (refused++ == 0) first_refusal = st.message();
      continue;
    }
    ++sent;
  }
  // Reliable samples still in flight are lost when the process exits: wait for the acknowledgements.
  for (auto& [channel, writer] : writer_of) writer->wait_for_acknowledgments(s.timeout());
  std::printf("replayed %llu messages on %zu topics in %.1f s at rate %g from %s\n",
              static_cast<unsigned long long>(sent), writer_of.size(), seconds_since(start), a.rate,
              a.file.c_str());
  if (refused > 0)
    return fail(std::to_string(refused) + " messages could not be published, the first: " + first_refusal);
  return 0;
}

}  // namespace

Handler add_record(CLI::App& cli) {
  auto a = std::make_shared<RecordArgs>();
  cli.add_option("file", a->file, "MCAP file to write (replaced if it exists)")->required();
  cli.add_option("--duration", a->duration_s, "seconds to record (default: until Ctrl-C)")
      ->check(CLI::PositiveNumber);
  cli.add_option("--topics", a->topics, "comma-separated topics to record (default: every topic)");
  return [a](Session& s) { return cmd_record(s, *a); };
}

Handler add_replay(CLI::App& cli) {
  auto a = std::make_shared<ReplayArgs>();
  cli.add_option("file", a->file, "MCAP file written by slamctl record")
      ->required()
      ->check(CLI::ExistingFile);
  cli.add_option("--rate", a->rate, "playback speed: 2 plays twice as fast")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cli.add_option("--topics", a->topics, "comma-separated topics to replay (default: every recorded topic)");
  return [a](Session& s) { return cmd_replay(s, *a); };
}

}  // namespace slam::ctl
