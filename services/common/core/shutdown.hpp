#pragma once
// Clean shutdown through one atomic flag, set by SIGINT/SIGTERM and polled by every loop.
#include <chrono>

namespace slam {

// Installs the SIGINT/SIGTERM handlers (idempotent).
void install_shutdown_handlers();

bool shutdown_requested();

// Sets the flag as a signal would (for tests and for fatal errors in a worker).
void request_shutdown();

// Sleeps up to `d`, returning early (true) when shutdown was requested.
bool wait_for_shutdown(std::chrono::milliseconds d);

}  // namespace slam
