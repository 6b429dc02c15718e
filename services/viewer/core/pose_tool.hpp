#pragma once
// The "Set pose" tool, as RViz's "2D Pose Estimate": armed for one robot, a press on the map marks
// where the robot truly is, dragging points along its heading, and the release gives the
// InitialPose to send. Escape or a right click cancels. It disarms after one use either way.
#include <optional>
#include <string>

#include "common/core/result.hpp"
#include "viewer/core/commands.hpp"

namespace slam::viewer {

class PoseTool {
 public:
  struct Arrow {
    Vec2 from;
    Vec2 to;
  };

  // Arms the tool for `robot_id`; an error (and not armed) unless it names one robot ("*" is all).
  Status arm(const std::string& robot_id);
  bool armed() const { return !robot_id_.empty(); }
  bool dragging() const { return press_.has_value(); }
  const std::string& robot_id() const { return robot_id_; }

  // Map-frame points. press() is ignored unless armed, drag() unless a press started.
  void press(Vec2 world);
  void drag(Vec2 world);
  // The pose: where the press was, heading towards `world`. A drag shorter than `min_drag_m`
  // gives no heading: nothing is returned and the tool stays armed for another try.
  std::optional<InitialPoseCommand> release(Vec2 world, double min_drag_m);
  void cancel();

  // From the press point to the cursor, while dragging.
  std::optional<Arrow> arrow() const;

 private:
  std::string robot_id_;  // empty: not armed
  std::optional<Vec2> press_;
  Vec2 cursor_;
};

}  // namespace slam::viewer
