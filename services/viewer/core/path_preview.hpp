#pragma once
// The "Preview path" tool: armed, a first click on the map is the start, a second the goal; the
// PathRequest goes to the planners and the reply is drawn with its length, or its status and
// reason when no path was found. Nothing is sent to any robot. Escape or a right click cancels.
#include <cstdint>
#include <optional>
#include <string>

#include "viewer/core/commands.hpp"
#include "viewer/core/request_tracker.hpp"

namespace slam::viewer {

class PathPreview {
 public:
  void arm();
  void cancel();
  bool armed() const { return stage_ != Stage::Idle; }
  // The start click, while the goal click is awaited.
  std::optional<Vec2> pending_start() const {
    return stage_ == Stage::Goal ? std::optional(start_) : std::nullopt;
  }

  // A click while armed: the start, then the goal (returned: the request to send; disarms).
  std::optional<PathPreviewCommand> click(Vec2 world);
  // The request went out under `id` (0: refused, nothing is awaited).
  void sent(const PathPreviewCommand& request, uint64_t id, int64_t now_ns);
  // A PathReply; kept when it answers the last request.
  void reply(msg::PathReply&& r);
  void tick(int64_t now_ns) { tracker_.tick(now_ns); }

  const std::optional<PathPreviewCommand>& request() const { return request_; }
  // The answer to the last request, once it came.
  const std::optional<msg::PathReply>& result() const { return result_; }
  // One line for the panel and the map: what to click, waiting, the length, or why it failed.
  std::string summary() const;
  void clear();

  std::string algorithm = "astar";  // astar or an OMPL planner

 private:
  enum class Stage : uint8_t { Idle, Start, Goal };
  Stage stage_ = Stage::Idle;
  Vec2 start_;
  std::optional<PathPreviewCommand> request_;
  std::optional<msg::PathReply> result_;
  RequestTracker tracker_;
};

}  // namespace slam::viewer
