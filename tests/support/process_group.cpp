#include "process_group.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace slam::testkit {

namespace {

// Locks domain `id`'s file; -1 when another process holds it.
int lock_domain(int id) {
  const std::string path = "/tmp/slamfleet-dds-domain-" + std::to_string(id) + ".lock";
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) return -1;
  if (flock(fd, LOCK_EX | LOCK_NB) == 0) return fd;
  ::close(fd);
  return -1;
}

}  // namespace

DomainLease::DomainLease(int count) {
  // Domains 20..100: a domain's ports are 7400 + 250 × id and up, and above id 100 they fall into
  // Linux's ephemeral range (32768 and up), where any client socket may hold one first and a
  // participant then fails with "address in use". The flock is released by the kernel even if the
  // test process crashes.
  constexpr int kFirst = 20, kCount = 81;
  if (count < 1 || count > kCount) throw std::invalid_argument("DomainLease: count must be 1..81");
  const int starts = kCount - count + 1;
  const int offset = static_cast<int>(getpid() % starts);
  for (int i = 0; i < starts; ++i) {
    const int id = kFirst + (offset + i) % starts;
    for (int k = 0; k < count; ++k) {
      const int fd = lock_domain(id + k);
      if (fd < 0) break;
      fds_.push_back(fd);
    }
    if (static_cast<int>(fds_.size()) == count) {
      id_ = id;
      return;
    }
    for (int fd : fds_) ::close(fd);
    fds_.clear();
  }
  throw std::runtime_error("no " + std::to_string(count) + " free DDS domain id(s) in a row in 20..100");
}

DomainLease::~DomainLease() {
  for (int fd : fds_) ::close(fd);
}

int free_tcp_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof addr;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    ::close(fd);
    throw std::runtime_error("cannot find a free TCP port");
  }
  ::close(fd);
  return ntohs(addr.sin_port);
}

bool wait_port_open(int port, std::chrono::milliseconds timeout) {
  return wait_until(
      [port] {
        const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_in addr{};
        addr.sin_family = AF_INET;
        addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        addr.sin_port = htons(static_cast<uint16_t>(port));
        const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
        ::close(fd);
        return ok;
      },
      timeout, 20ms);
}

bool wait_until(const std::function<bool()>& pred, std::chrono::milliseconds timeout,
                std::chrono::milliseconds poll) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (pred()) return true;
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(poll);
  }
}

bool dds_security_on() {
  const char* dir = std::getenv("SLAM_DDS_SECURITY_DIR");
  return dir != nullptr && *dir != '\0';
}

std::vector<std::string> with_dds_identity(const std::string& identity, std::vector<std::string> argv) {
  if (dds_security_on()) argv.insert(argv.begin(), {"env", "SLAM_DDS_IDENTITY=" + identity});
  return argv;
}

std::string bin_path(const std::string& name) {
  return std::string(SLAM_BIN_DIR) + "/" + name;
}

namespace {

// State and process group of `pid` from /proc/<pid>/stat; nullopt when it is gone.
std::optional<std::pair<char, pid_t>> process_state(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return std::nullopt;
  // Fields after the ")" closing the command name: state ppid pgrp ...
  const auto close = line.rfind(')');
  if (close == std::string::npos || close + 2 >= line.size()) return std::nullopt;
  std::istringstream rest(line.substr(close + 2));
  char state = 0;
  pid_t ppid = 0, pgrp = 0;
  if (!(rest >> state >> ppid >> pgrp)) return std::nullopt;
  return std::pair(state, pgrp);
}

}  // namespace

bool process_alive(pid_t pid) {
  const auto s = process_state(pid);
  return s && s->first != 'Z' && s->first != 'X';
}

std::vector<pid_t> process_group_members(pid_t pgid) {
  std::vector<pid_t> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = std::stoi(name);
    const auto s = process_state(pid);
    if (s && s->second == pgid && s->first != 'Z' && s->first != 'X') out.push_back(pid);
  }
  return out;
}

ProcessGroup::ProcessGroup() {
  char tmpl[] = "/tmp/slamfleet-test-XXXXXX";
  if (!mkdtemp(tmpl)) throw std::runtime_error("mkdtemp failed");
  dir_ = tmpl;
}

ProcessGroup::~ProcessGroup() {
  for (auto& [name, c] : children_)
    if (!c.reaped) ::kill(-c.pid, SIGTERM);
  const auto until = std::chrono::steady_clock::now() + 3s;
  for (auto& [name, c] : children_) {
    while (!c.reaped && !reap(c, false) && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(10ms);
    if (!c.reaped) {
      ::kill(-c.pid, SIGKILL);
      reap(c, true);
    }
    ::kill(-c.pid, SIGKILL);  // stragglers the process left in its group
  }
  const bool failed = ::testing::Test::HasFailure();
  if (failed) {
    for (const auto& [name, c] : children_)
      std::cerr << "----- log of " << name << " (pid " << c.pid << ") -----\n" << log(name) << "\n";
  }
  if (std::getenv("SLAM_KEEP_TEST_LOGS") == nullptr) {
    std::filesystem::remove_all(dir_);
  } else {
    std::cerr << "logs kept in " << dir_ << "\n";
  }
}

pid_t ProcessGroup::start(const std::string& name, const std::vector<std::string>& argv) {
  if (children_.count(name) && !children_[name].reaped)
    throw std::runtime_error("process " + name + " is already running");
  const std::string log_path = dir_ + "/" + name + ".log";
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    ::setpgid(0, 0);                          // own group: teardown kills its children too
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);       // and a crashed test takes it down
    if (::getppid() != parent) ::_exit(127);  // the test died before the line above
    const int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execvp(args[0], args.data());
    std::fprintf(stderr, "exec %s failed: %s\n", args[0], std::strerror(errno));
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  children_[name] = Child{pid, false, 0};
  return pid;
}

std::string ProcessGroup::write_mosquitto_config(const std::string& name, int port,
                                                 const std::string& address) {
  const std::string path = dir_ + "/" + name + ".conf";
  std::ofstream conf(path);
  // Started as root, mosquitto would switch to user "mosquitto"; a credential change clears the
  // parent-death signal, and the broker would outlive a crashed test. "root" means no switch.
  if (::geteuid() == 0) conf << "user root\n";
  conf << "listener " << port << " " << address << "\n"
       << "allow_anonymous true\n"
       << "persistence false\n"
       << "log_dest stderr\n"
       << "max_queued_messages 100000\n"
       << "sys_interval 1\n";  // $SYS counters once a second (bench_pipeline reads the broker's drops)
  return path;
}

int ProcessGroup::start_mosquitto(const std::string& name) {
  const int port = free_tcp_port();
  restart_mosquitto(name, port);
  return port;
}

void ProcessGroup::restart_mosquitto(const std::string& name, int port) {
  start(name, {"mosquitto", "-c", write_mosquitto_config(name, port)});
  if (!wait_port_open(port, 5s))
    throw std::runtime_error("mosquitto did not open port " + std::to_string(port));
}

bool ProcessGroup::reap(Child& c, bool block) {
  if (c.reaped) return true;
  int status = 0;
  const pid_t r = ::waitpid(c.pid, &status, block ? 0 : WNOHANG);
  if (r == c.pid) {
    c.reaped = true;
    c.status = status;
  }
  return c.reaped;
}

bool ProcessGroup::running(const std::string& name) {
  auto it = children_.find(name);
  return it != children_.end() && !reap(it->second, false);
}

void ProcessGroup::stop(const std::string& name, int sig) {
  auto it = children_.find(name);
  if (it == children_.end() || it->second.reaped) return;
  ::kill(-it->second.pid, sig);
  if (sig == SIGKILL || sig == SIGTERM) {
    if (!wait_until([&] { return reap(it->second, false); }, 5s)) {
      ::kill(-it->second.pid, SIGKILL);
      reap(it->second, true);
    }
  }
}

int ProcessGroup::wait_exit(const std::string& name, std::chrono::milliseconds timeout) {
  auto it = children_.find(name);
  if (it == children_.end()) return -1;
  if (!wait_until([&] { return reap(it->second, false); }, timeout)) return -1;
  return WIFEXITED(it->second.status) ? WEXITSTATUS(it->second.status) : -1;
}

std::string ProcessGroup::log(const std::string& name) const {
  std::ifstream in(dir_ + "/" + name + ".log");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<pid_t> ProcessGroup::pids() const {
  std::vector<pid_t> out;
  for (const auto& [name, c] : children_) out.push_back(c.pid);
  return out;
}

}  // namespace slam::testkit
