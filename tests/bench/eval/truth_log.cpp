// The truth log's text format (truth_log.hpp).
#include "eval/truth_log.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace slam::bench {

namespace {

// The next space-separated field of `line` (advanced past it); empty when there is none.
std::string_view next_field(std::string_view& line) {
  const size_t start = line.find_first_not_of(' ');
  if (start == std::string_view::npos) {
    line = {};
    return {};
  }
  line.remove_prefix(start);
  const size_t end = std::min(line.find(' '), line.size());
  const std::string_view field = line.substr(0, end);
  line.remove_prefix(end);
  return field;
}

template <class T>
bool parse_number(std::string_view field, T& out) {
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), out);
  return ec == std::errc{} && end == field.data() + field.size();
}

}  // namespace

Status write_truth_log(const std::filesystem::path& path, std::span<const TruthSample> samples) {
  std::ofstream out(path);
  if (!out) return Error{"cannot write " + path.string()};
  out << "# stamp_ns robot true_x true_y true_theta odom_x odom_y odom_theta\n";
  for (const TruthSample& s : samples) {
    const Pose& t = s.truth.true_pose;
    const Pose& o = s.truth.reported_pose;
    out << fmt::format("{} {} {:.5f} {:.5f} {:.6f} {:.5f} {:.5f} {:.6f}\n", s.stamp_ns, s.truth.robot_id, t.x,
                       t.y, t.theta, o.x, o.y, o.theta);
  }
  out.flush();
  if (!out) return Error{"writing " + path.string() + " failed"};
  return Status::ok();
}

Result<std::vector<TruthSample>> parse_truth_log(std::string_view text) {
  std::vector<TruthSample> out;
  size_t line_number = 0;
  while (!text.empty()) {
    const size_t eol = std::min(text.find('\n'), text.size());
    std::string_view line = text.substr(0, eol);
    text.remove_prefix(std::min(eol + 1, text.size()));
    ++line_number;
    if (line.find_first_not_of(' ') == std::string_view::npos || line.front() == '#') continue;
    const auto fail = [&](std::string_view why) {
      return Error{fmt::format("truth log line {}: {}", line_number, why)};
    };
    TruthSample s;
    if (!parse_number(next_field(line), s.stamp_ns)) return fail("the stamp is not an integer");
    const std::string_view robot = next_field(line);
    if (robot.empty()) return fail("no robot id");
    s.truth.robot_id = std::string(robot);
    double v[6];
    for (double& x : v) {
      if (!parse_number(next_field(line), x) || !std::isfinite(x))
        return fail("expected 6 finite numbers after the robot id");
    }
    if (!next_field(line).empty()) return fail("more than 8 fields");
    if (!out.empty() && s.stamp_ns < out.back().stamp_ns) return fail("the stamp goes back");
    s.truth.true_pose = {v[0], v[1], v[2]};
    s.truth.reported_pose = {v[3], v[4], v[5]};
    out.push_back(std::move(s));
  }
  return out;
}

Result<std::vector<TruthSample>> read_truth_log(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return Error{"cannot read " + path.string()};
  std::stringstream text;
  text << in.rdbuf();
  auto parsed = parse_truth_log(text.str());
  if (!parsed) return Error{path.string() + ": " + parsed.message()};
  return parsed;
}

}  // namespace slam::bench
