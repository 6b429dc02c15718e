#pragma once
// The alerts panel's data: the latest state of every alert the planners published (slam/system/alert),
// active ones listed newest first. Plain; the render thread owns it.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "viewer/core/intake_types.hpp"

namespace slam::viewer {

class AlertBoard {
 public:
  // The alert's latest state replaces the one kept.
  void update(msg::Alert&& a);
  // Active alerts, the most recently raised first.
  std::vector<const msg::Alert*> active() const;
  std::size_t active_count() const;

 private:
  std::map<std::string, msg::Alert> alerts_;  // by alert id
};

// "battery low  sim-1  12 s ago: robot 'sim-1' battery 10 % (below 20 %): sent home"
std::string describe(const msg::Alert& a, int64_t now_wall_ns);

}  // namespace slam::viewer
