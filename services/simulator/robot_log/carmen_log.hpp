#pragma once
// Reading a whole CARMEN log: plain text or gzip (zlib reads either, so neither the extension nor
// the magic needs checking), line by line. Bad lines are counted and skipped; only a file that
// cannot be opened or whose gzip stream breaks is an error.
#include <filesystem>
#include <string_view>

#include "common/core/result.hpp"
#include "simulator/robot_log/carmen_line.hpp"
#include "simulator/robot_log/robot_log.hpp"

namespace slam::robot_log {

// Feeds lines in file order and keeps the scans and the stats.
class CarmenLogBuilder {
 public:
  explicit CarmenLogBuilder(CarmenOptions options = {}) : options_(options) {}
  void add_line(std::string_view line);
  // A line too long to keep counts as bad (the reader skips the rest of it).
  void add_bad_line(std::string_view reason);
  RobotLog take() { return std::move(log_); }

 private:
  void mark_bad(std::string_view reason);

  CarmenOptions options_;
  CarmenContext context_;
  RobotLog log_;
};

// The lines of `text` (tests, fuzzing).
RobotLog parse_carmen_text(std::string_view text, const CarmenOptions& options = {});

Result<RobotLog> read_carmen_log(const std::filesystem::path& path, const CarmenOptions& options = {});

}  // namespace slam::robot_log
