// Reading a robot log of either format (read_robot_log.hpp).
#include "simulator/robot_log/read_robot_log.hpp"

#include <algorithm>
#include <array>
#include <fstream>

#include "common/core/mcap_records.hpp"
#include "simulator/robot_log/carmen_log.hpp"

namespace slam::robot_log {

Result<LogFormat> detect_log_format(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{"cannot open " + path.string()};
  std::array<char, mcap::kMagic.size()> head{};
  in.read(head.data(), head.size());
  const bool mcap = in.gcount() == static_cast<std::streamsize>(head.size()) &&
                    std::equal(head.begin(), head.end(), mcap::kMagic.begin(),
                               [](char a, uint8_t b) { return static_cast<uint8_t>(a) == b; });
  return mcap ? LogFormat::Ros2Mcap : LogFormat::Carmen;
}

Result<RobotLog> read_robot_log(const std::filesystem::path& path, const ReadOptions& options) {
  auto format = detect_log_format(path);
  if (!format) return format.error();
  if (*format == LogFormat::Ros2Mcap) return read_ros2_mcap_log(path, options.ros2);
  return read_carmen_log(path, options.carmen);
}

}  // namespace slam::robot_log
