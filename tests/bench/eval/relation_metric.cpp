// The benchmark's relation metric (relation_metric.hpp).
#include "eval/relation_metric.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>

namespace slam::bench {

namespace {

// Splits on spaces and tabs and parses every field as a double; nullopt on a non-number.
std::optional<std::vector<double>> numbers(std::string_view line) {
  std::vector<double> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i >= line.size()) break;
    size_t end = i;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != '\r') ++end;
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(line.data() + i, line.data() + end, v);
    if (ec != std::errc{} || ptr != line.data() + end || !std::isfinite(v)) return std::nullopt;
    out.push_back(v);
    i = end;
  }
  return out;
}

MeanStd mean_std(std::span<const double> values) {
  MeanStd out;
  if (values.empty()) return out;
  double sum = 0.0;
  for (double v : values) sum += v;
  out.mean = sum / static_cast<double>(values.size());
  double var = 0.0;
  for (double v : values) var += (v - out.mean) * (v - out.mean);
  out.std = std::sqrt(var / static_cast<double>(values.size()));
  return out;
}

}  // namespace

Result<Relation> parse_relation(std::string_view line) {
  const auto fields = numbers(line);
  if (!fields) return Error{"a field is not a finite number"};
  if (fields->size() != 8)
    return Error{fmt::format("{} fields, expected 8 (t1 t2 x y z roll pitch yaw)", fields->size())};
  const auto& f = *fields;
  return Relation{f[0], f[1], Pose{f[2], f[3], wrap_angle(f[7])}};
}

Result<std::vector<Relation>> read_relations(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return Error{"cannot open relation file " + path.string()};
  std::vector<Relation> out;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    auto relation = parse_relation(line);
    if (!relation) return Error{fmt::format("{} line {}: {}", path.string(), number, relation.message())};
    out.push_back(*relation);
  }
  if (out.empty()) return Error{path.string() + " holds no relation"};
  return out;
}

StampedPoses::StampedPoses(std::span<const double> stamps, std::span<const Pose> poses, double tolerance_s)
    : tolerance_s_(tolerance_s) {
  const size_t n = std::min(stamps.size(), poses.size());
  entries_.reserve(n);
  for (size_t i = 0; i < n; ++i) entries_.push_back({stamps[i], poses[i]});
  std::stable_sort(entries_.begin(), entries_.end(),
                   [](const Entry& a, const Entry& b) { return a.stamp < b.stamp; });
}

std::optional<Pose> StampedPoses::at(double stamp) const {
  auto it = std::lower_bound(entries_.begin(), entries_.end(), stamp,
                             [](const Entry& e, double s) { return e.stamp < s; });
  const Entry* best = nullptr;
  if (it != entries_.end()) best = &*it;
  if (it != entries_.begin() && (!best || stamp - std::prev(it)->stamp < best->stamp - stamp))
    best = &*std::prev(it);
  if (!best || std::abs(best->stamp - stamp) > tolerance_s_) return std::nullopt;
  return best->pose;
}

RelationScore score_relations(std::span<const Relation> relations, const StampedPoses& estimate,
                              double min_duration_s, double max_duration_s) {
  RelationScore score;
  std::vector<double> trans, trans_sq, rot, rot_sq;
  for (const Relation& r : relations) {
    const double duration = std::abs(r.t2 - r.t1);
    if (duration < min_duration_s || duration > max_duration_s) continue;
    const auto x1 = estimate.at(r.t1);
    const auto x2 = estimate.at(r.t2);
    if (!x1 || !x2) {
      ++score.missing;
      continue;
    }
    const Pose error = r.motion.inverse().compose(x1->inverse().compose(*x2));
    const double t = norm(error.position());
    const double a = std::abs(to_degrees(wrap_angle(error.theta)));
    trans.push_back(t);
    trans_sq.push_back(t * t);
    rot.push_back(a);
    rot_sq.push_back(a * a);
  }
  score.relations = trans.size();
  score.trans_abs = mean_std(trans);
  score.trans_sq = mean_std(trans_sq);
  score.rot_abs = mean_std(rot);
  score.rot_sq = mean_std(rot_sq);
  return score;
}

std::string describe(const RelationScore& s) {
  return fmt::format("{:.3f} ± {:.3f} m, {:.2f} ± {:.2f}°", s.trans_abs.mean, s.trans_abs.std, s.rot_abs.mean,
                     s.rot_abs.std);
}

}  // namespace slam::bench
