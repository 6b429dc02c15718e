// Alerts kept by id (see alert_board.hpp).
#include "viewer/core/alert_board.hpp"

#include <algorithm>
#include <cstdio>

namespace slam::viewer {

void AlertBoard::update(msg::Alert&& a) {
  std::string id = a.alert_id;
  alerts_[std::move(id)] = std::move(a);
}

std::vector<const msg::Alert*> AlertBoard::active() const {
  std::vector<const msg::Alert*> out;
  for (const auto& [id, a] : alerts_)
    if (a.active) out.push_back(&a);
  std::stable_sort(out.begin(), out.end(),
                   [](const msg::Alert* x, const msg::Alert* y) { return x->raised_ns > y->raised_ns; });
  return out;
}

std::size_t AlertBoard::active_count() const {
  return static_cast<std::size_t>(
      std::count_if(alerts_.begin(), alerts_.end(), [](const auto& entry) { return entry.second.active; }));
}

std::string describe(const msg::Alert& a, int64_t now_wall_ns) {
  char age[32];
  std::snprintf(age, sizeof age, "%.0f s ago", static_cast<double>(now_wall_ns - a.raised_ns) * 1e-9);
  return std::string(alerts::kind_name(a.kind)) + "  " + a.subject + "  " + age + ": " + a.message;
}

}  // namespace slam::viewer
