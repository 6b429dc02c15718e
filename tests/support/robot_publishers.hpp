#pragma once
// The robots' side of an MQTT load: one `mosquitto_pub -l` per robot, each line one message at QoS 1
// on that robot's topic. Pipelined, unlike MqttTestClient, which waits for each acknowledgement
// (~100 ms on loopback).
#include <stdio.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace slam::testkit {

class RobotPublishers {
 public:
  // One publisher per topic, client ids `client_prefix`-0, -1, ...
  RobotPublishers(int port, const std::vector<std::string>& topics, const std::string& client_prefix) {
    for (size_t i = 0; i < topics.size(); ++i) {
      const std::string command = "mosquitto_pub -h 127.0.0.1 -p " + std::to_string(port) + " -q 1 -i " +
                                  client_prefix + "-" + std::to_string(i) + " -t " + topics[i] + " -l";
      pipes_.push_back(::popen(command.c_str(), "w"));
    }
  }
  ~RobotPublishers() { close(); }
  RobotPublishers(const RobotPublishers&) = delete;
  RobotPublishers& operator=(const RobotPublishers&) = delete;

  bool ok() const {
    return std::all_of(pipes_.begin(), pipes_.end(), [](FILE* f) { return f != nullptr; });
  }
  // `line` (no newline) as one message of robot `i`.
  void publish(size_t i, std::string_view line) {
    FILE* f = pipes_.at(i);
    std::fwrite(line.data(), 1, line.size(), f);
    std::fputc('\n', f);
    std::fflush(f);
  }
  void publish_all(std::string_view line) {
    for (size_t i = 0; i < pipes_.size(); ++i) publish(i, line);
  }
  // Ends input; each publisher sends what it has and exits.
  void close() {
    for (FILE* f : pipes_)
      if (f) ::pclose(f);
    pipes_.clear();
  }

 private:
  std::vector<FILE*> pipes_;
};

}  // namespace slam::testkit
