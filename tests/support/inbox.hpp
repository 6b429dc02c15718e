#pragma once
// Samples a callback collects on another thread (a DDS listener, an MQTT client), read and waited on
// by the test thread. Transport-free: the DDS-using code feeds it with push().
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>
#include <vector>

namespace slam::testkit {

template <class T>
class Inbox {
 public:
  void push(const T& sample) {
    {
      std::lock_guard lock(mutex_);
      items_.push_back(sample);
    }
    arrived_.notify_all();
  }
  std::vector<T> items() const {
    std::lock_guard lock(mutex_);
    return items_;
  }
  size_t size() const {
    std::lock_guard lock(mutex_);
    return items_.size();
  }
  void clear() {
    std::lock_guard lock(mutex_);
    items_.clear();
  }
  // The newest sample matching `pred`.
  template <class Pred>
  std::optional<T> last(Pred pred) const {
    std::lock_guard lock(mutex_);
    for (auto it = items_.rbegin(); it != items_.rend(); ++it)
      if (pred(*it)) return *it;
    return std::nullopt;
  }
  // Waits until a sample matching `pred` has arrived (now or within `timeout`) and returns the newest one.
  template <class Pred>
  std::optional<T> wait_for(Pred pred, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    std::optional<T> found;
    arrived_.wait_for(lock, timeout, [&] {
      for (auto it = items_.rbegin(); it != items_.rend(); ++it)
        if (pred(*it)) {
          found = *it;
          return true;
        }
      return false;
    });
    return found;
  }
  // Waits until at least `count` samples have arrived; false on timeout.
  bool wait_size(size_t count, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    return arrived_.wait_for(lock, timeout, [&] { return items_.size() >= count; });
  }

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable arrived_;
  std::vector<T> items_;
};

}  // namespace slam::testkit
