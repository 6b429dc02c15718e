// Ground-truth relations (truth_relations.hpp).
#include "simulator/core/truth_relations.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "simulator/core/carmen_writer.hpp"

namespace slam::sim {

namespace {

// Simulated stamps are sums of dt: 1.3 - 0.3 may come out a hair under 1.
constexpr double kStampSlackS = 1e-6;

TruthRelation relation(const TruthSample& a, const TruthSample& b) {
  return {a.stamp_s, b.stamp_s, a.pose.inverse().compose(b.pose)};
}

}  // namespace

Status RelationPlan::validate() const {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!positive(step_s)) return Error{fmt::format("step_s must be finite and > 0, not {}", step_s)};
  if (!positive(long_span_s) || long_span_s < step_s)
    return Error{fmt::format("long_span_s must be finite and >= step_s ({}), not {}", step_s, long_span_s)};
  if (!positive(long_every_s))
    return Error{fmt::format("long_every_s must be finite and > 0, not {}", long_every_s)};
  return Status::ok();
}

std::vector<TruthRelation> pick_relations(std::span<const TruthSample> track, const RelationPlan& plan) {
  std::vector<size_t> anchors;
  for (size_t i = 0; i < track.size(); ++i)
    if (anchors.empty() || track[i].stamp_s - track[anchors.back()].stamp_s >= plan.step_s - kStampSlackS)
      anchors.push_back(i);

  std::vector<TruthRelation> out;
  for (size_t k = 1; k < anchors.size(); ++k)
    out.push_back(relation(track[anchors[k - 1]], track[anchors[k]]));

  bool started = false;
  double last_long_s = 0;
  size_t reach = 0;  // the long relation's far anchor only moves forward
  for (size_t k = 0; k < anchors.size(); ++k) {
    const TruthSample& from = track[anchors[k]];
    if (started && from.stamp_s - last_long_s < plan.long_every_s - kStampSlackS) continue;
    reach = std::max(reach, k + 1);
    while (reach < anchors.size() &&
           track[anchors[reach]].stamp_s - from.stamp_s < plan.long_span_s - kStampSlackS)
      ++reach;
    if (reach >= anchors.size()) break;
    out.push_back(relation(from, track[anchors[reach]]));
    started = true;
    last_long_s = from.stamp_s;
  }
  return out;
}

void append_relation_line(const TruthRelation& r, std::string& out) {
  fmt::format_to(std::back_inserter(out), "{} {} {:.6f} {:.6f} 0 0 0 {:.9f}\n", stamp_text(r.t1_s),
                 stamp_text(r.t2_s), r.motion.x, r.motion.y, r.motion.theta);
}

}  // namespace slam::sim
