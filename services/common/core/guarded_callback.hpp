#pragma once
// The one exception guard for callbacks a C library calls (paho MQTT, GLFW, DDS listeners): an
// exception unwinding into C code is undefined behaviour, so everything is caught here, logged as
// one line naming the callback, and the callback returns a value that is safe for the library.
#include <spdlog/spdlog.h>

#include <exception>
#include <type_traits>
#include <utility>

namespace slam {

namespace detail {

inline void log_callback_failure(const char* where, const char* what) noexcept {
  try {
    if (what != nullptr) {
      spdlog::error("{} callback failed: {}", where, what);
    } else {
      spdlog::error("{} callback failed with a non-standard exception", where);
    }
  } catch (...) {  // logging itself failed: nothing more can be done inside a C callback
  }
}

}  // namespace detail

// Runs `fn()` and returns its result; when it throws, logs "<where> callback failed: ..." and
// returns `safe` instead.
// (enable_if rather than requires: the bridge's WebSocket edge includes this as C++17, since
// websocketpp 0.8 does not build as C++20.)
template <class F, class R = std::invoke_result_t<F&>, std::enable_if_t<!std::is_void_v<R>, int> = 0>
R guarded_callback(const char* where, R safe, F&& fn) noexcept {
  try {
    return fn();
  } catch (const std::exception& e) {
    detail::log_callback_failure(where, e.what());
  } catch (...) {
    detail::log_callback_failure(where, nullptr);
  }
  return safe;
}

// Runs `fn()`; when it throws, logs "<where> callback failed: ..." and returns normally.
template <class F, std::enable_if_t<std::is_void_v<std::invoke_result_t<F&>>, int> = 0>
void guarded_callback(const char* where, F&& fn) noexcept {
  try {
    fn();
  } catch (const std::exception& e) {
    detail::log_callback_failure(where, e.what());
  } catch (...) {
    detail::log_callback_failure(where, nullptr);
  }
}

}  // namespace slam
