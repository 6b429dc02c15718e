#pragma once
// Process-group harness for integration tests: starts real processes (mosquitto, service binaries)
// with their output in per-test log files, waits for readiness, and at teardown kills every process
// and its children, even when the test failed. Logs are printed when the test failed.
#include <sys/types.h>

#include <chrono>
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <vector>

namespace slam::testkit {

using namespace std::chrono_literals;

// A DDS domain id held exclusively by this process (flock on a file in /tmp) for its lifetime, so
// parallel tests never share a domain. `count` > 1 holds id() .. id() + count - 1, for a test whose
// system uses the next domains too (the secure launcher puts the simulator on domain + 1).
class DomainLease {
 public:
  explicit DomainLease(int count = 1);
  ~DomainLease();
  DomainLease(const DomainLease&) = delete;
  DomainLease& operator=(const DomainLease&) = delete;
  int id() const { return id_; }

 private:
  int id_ = -1;
  std::vector<int> fds_;
};

// A loopback TCP port that was free a moment ago.
int free_tcp_port();
bool wait_port_open(int port, std::chrono::milliseconds timeout);

// Polls `pred` every `poll` until it is true or `timeout` passes.
bool wait_until(const std::function<bool()>& pred, std::chrono::milliseconds timeout,
                std::chrono::milliseconds poll = 10ms);

// Path of a project binary (service, tool) in the build tree.
std::string bin_path(const std::string& name);

// argv run as DDS identity `identity` (env SLAM_DDS_IDENTITY=...) when this process itself runs
// on a secure domain (SLAM_DDS_SECURITY_DIR set: docs/security.md, benches with security on);
// otherwise argv unchanged.
std::vector<std::string> with_dds_identity(const std::string& identity, std::vector<std::string> argv);
// True when SLAM_DDS_SECURITY_DIR is set.
bool dds_security_on();

// Whether `pid` is a live process (not gone, not a zombie), from /proc.
bool process_alive(pid_t pid);
// Pids of the live processes whose process group is `pgid`, from /proc.
std::vector<pid_t> process_group_members(pid_t pgid);

class ProcessGroup {
 public:
  ProcessGroup();
  ~ProcessGroup();
  ProcessGroup(const ProcessGroup&) = delete;
  ProcessGroup& operator=(const ProcessGroup&) = delete;

  // Starts argv[0] (a path, or a name searched in PATH) as `name`; stdout+stderr go to dir()/name.log.
  // The process gets its own process group and dies with the thread that started it (a crashed
  // test leaves nothing behind), as long as it does not change its credentials.
  pid_t start(const std::string& name, const std::vector<std::string>& argv);
  // Starts mosquitto on a free loopback port with a generated config; returns the port once it accepts.
  // It keeps the test's user, so it dies with the test too.
  int start_mosquitto(const std::string& name = "mosquitto");
  // Same config and port as an earlier start_mosquitto (for broker-restart tests).
  void restart_mosquitto(const std::string& name, int port);
  // Writes the config start_mosquitto uses, listening on `address`, and returns its path: for a
  // broker started some other way (e.g. in a network namespace).
  std::string write_mosquitto_config(const std::string& name, int port,
                                     const std::string& address = "127.0.0.1");

  bool running(const std::string& name);
  // Sends `sig` to the process's whole group and, for SIGKILL/SIGTERM, waits for it to exit.
  void stop(const std::string& name, int sig = 15);
  // Waits for the process to exit by itself; returns its exit code, or -1 on timeout / signal.
  int wait_exit(const std::string& name, std::chrono::milliseconds timeout);
  std::string log(const std::string& name) const;
  const std::string& dir() const { return dir_; }
  std::vector<pid_t> pids() const;
  pid_t pid(const std::string& name) const { return children_.at(name).pid; }

 private:
  struct Child {
    pid_t pid = -1;
    bool reaped = false;
    int status = 0;
  };
  bool reap(Child& c, bool block);

  std::string dir_;
  std::map<std::string, Child> children_;
};

}  // namespace slam::testkit
