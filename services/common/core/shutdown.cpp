#include "common/core/shutdown.hpp"

#include <atomic>
#include <csignal>
#include <thread>

namespace slam {
namespace {

std::atomic<bool> g_shutdown{false};

extern "C" void on_signal(int) {
  g_shutdown.store(true);
}

}  // namespace

void install_shutdown_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);
}

bool shutdown_requested() {
  return g_shutdown.load(std::memory_order_relaxed);
}

void request_shutdown() {
  g_shutdown.store(true);
}

bool wait_for_shutdown(std::chrono::milliseconds d) {
  // Short sleeps: the flag cannot wake a condition variable from a signal handler safely.
  const auto until = std::chrono::steady_clock::now() + d;
  while (!shutdown_requested()) {
    const auto left = until - std::chrono::steady_clock::now();
    if (left <= std::chrono::milliseconds::zero()) return false;
    std::this_thread::sleep_for(
        std::min<std::chrono::steady_clock::duration>(left, std::chrono::milliseconds(20)));
  }
  return true;
}

}  // namespace slam
