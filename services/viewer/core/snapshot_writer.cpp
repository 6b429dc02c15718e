// The snapshot writer thread and the snapshot directory (see snapshot_writer.hpp).
#include "viewer/core/snapshot_writer.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <system_error>
#include <utility>

namespace slam::viewer {

Result<uint32_t> prepare_snapshot_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return Error{"cannot create --snapshot-dir " + dir + ": " + ec.message()};
  if (!fs::is_directory(dir, ec)) return Error{"--snapshot-dir " + dir + " is not a directory"};
  uint32_t highest = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (auto index = parse_snapshot_file_name(it->path().filename().string()))
      highest = std::max(highest, *index);
  if (ec) return Error{"cannot list --snapshot-dir " + dir + ": " + ec.message()};
  return highest + 1;
}

SnapshotWriter::SnapshotWriter() : thread_([this] { run(); }) {}

SnapshotWriter::~SnapshotWriter() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

bool SnapshotWriter::submit(SnapshotJob&& job) {
  {
    std::lock_guard lock(mutex_);
    if (pending_ || busy_) {
      ++dropped_;
      return false;
    }
    pending_ = std::move(job);
  }
  wake_.notify_one();
  return true;
}

void SnapshotWriter::wait_idle() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return !pending_ && !busy_; });
}

uint64_t SnapshotWriter::written() const {
  std::lock_guard lock(mutex_);
  return written_;
}

uint64_t SnapshotWriter::failed() const {
  std::lock_guard lock(mutex_);
  return failed_;
}

uint64_t SnapshotWriter::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

Status SnapshotWriter::write(const SnapshotJob& job) {
  auto bytes = encode_png(job.image);
  if (!bytes) return Error{"snapshot " + job.names.path + ": " + bytes.message()};
  if (Status s = write_file_atomically(job.names.path, job.names.temp_path, *bytes); !s) return s;
  if (Status s = write_file_atomically(job.names.latest, job.names.latest_temp, *bytes); !s) return s;
  if (!job.names.expired.empty()) {
    std::error_code ec;  // already gone is fine: an operator may clean the directory
    std::filesystem::remove(job.names.expired, ec);
  }
  return {};
}

void SnapshotWriter::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return pending_ || stopping_; });
    if (!pending_) break;  // stopping with nothing left to write
    SnapshotJob job = std::move(*pending_);
    pending_.reset();
    busy_ = true;
    lock.unlock();
    const auto t0 = std::chrono::steady_clock::now();
    const Status s = write(job);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (s) {
      spdlog::info("snapshot {} written ({}x{}, encoded and stored in {:.0f} ms{}{})", job.names.path,
                   job.image.width, job.image.height, ms, job.summary.empty() ? "" : ", ", job.summary);
    } else {
      spdlog::error("{}", s.message());
    }
    lock.lock();
    busy_ = false;
    (s ? written_ : failed_) += 1;
    idle_.notify_all();
  }
}

}  // namespace slam::viewer
