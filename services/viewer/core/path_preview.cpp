// Two clicks -> PathRequest -> the reply kept for drawing (see path_preview.hpp).
#include "viewer/core/path_preview.hpp"

#include <cstdio>

namespace slam::viewer {

void PathPreview::arm() {
  stage_ = Stage::Start;
}

void PathPreview::cancel() {
  stage_ = Stage::Idle;
}

std::optional<PathPreviewCommand> PathPreview::click(Vec2 world) {
  switch (stage_) {
    case Stage::Idle:
      return std::nullopt;
    case Stage::Start:
      start_ = world;
      stage_ = Stage::Goal;
      return std::nullopt;
    case Stage::Goal:
      stage_ = Stage::Idle;
      return PathPreviewCommand{start_, world, algorithm};
  }
  return std::nullopt;
}

void PathPreview::sent(const PathPreviewCommand& request, uint64_t id, int64_t now_ns) {
  request_ = request;
  result_.reset();
  if (id == 0) {
    tracker_ = RequestTracker{};  // nothing to wait for: summary() says it was not sent
  } else {
    tracker_.sent(id, "path request", now_ns);
  }
}

void PathPreview::reply(msg::PathReply&& r) {
  if (!tracker_.reply(r.request_id, r.status == msg::PlanStatus::Ok, r.reason)) return;
  result_ = std::move(r);
}

std::string PathPreview::summary() const {
  if (stage_ == Stage::Start) return "click the start on the map";
  if (stage_ == Stage::Goal) return "click the goal on the map";
  if (!request_) return "no path previewed";
  char line[384];
  if (result_) {
    if (result_->status == msg::PlanStatus::Ok) {
      std::snprintf(line, sizeof line, "path %.2f m, %zu points (%s, %.1f ms)", result_->length_m,
                    result_->path.size(), request_->algorithm.c_str(), result_->planning_time_s * 1e3);
    } else {
      std::snprintf(line, sizeof line, "no path: %s", result_->reason.c_str());
    }
    return line;
  }
  const auto& last = tracker_.last();
  if (!last) return "path request NOT sent (the DDS writer refused it)";
  if (last->state == RequestState::NoReply) return "no reply from a planner (is one running?)";
  return "waiting for a planner";
}

void PathPreview::clear() {
  stage_ = Stage::Idle;
  request_.reset();
  result_.reset();
}

}  // namespace slam::viewer
