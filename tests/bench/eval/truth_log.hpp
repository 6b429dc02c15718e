#pragma once
// A run's sampled ground truth as a text file, so the run's stored observations can be replayed
// offline (eval_replay) and scored against the same instants. One line per robot and instant:
//   stamp_ns robot true_x true_y true_theta odom_x odom_y odom_theta
// (metres, radians; `#` starts a comment line). The stamp is the observations' clock.
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "common/core/result.hpp"
#include "eval/run_recorder.hpp"

namespace slam::bench {

Status write_truth_log(const std::filesystem::path& path, std::span<const TruthSample> samples);

// Errors name the line: a missing field, a number that does not parse or is not finite, a stamp
// going back.
Result<std::vector<TruthSample>> parse_truth_log(std::string_view text);
Result<std::vector<TruthSample>> read_truth_log(const std::filesystem::path& path);

}  // namespace slam::bench
