// IDL <-> core conversions for slam-mapper (see mapper_msgs.hpp).
#include "mapper/dds/mapper_msgs.hpp"

#include <cmath>
#include <string>

namespace slam::mapper {
namespace {

void copy_points(const std::vector<slam::Point2>& in, std::vector<Vec2>& out) {
  out.resize(in.size());
  for (size_t i = 0; i < in.size(); ++i) out[i] = Vec2{in[i].x(), in[i].y()};
}

}  // namespace

Result<ObservationView> to_view(const slam::RobotObservation& in, std::vector<Vec2>& hits,
                                std::vector<Vec2>& misses) {
  if (in.robot_id().size() == 0) return Error{"robot_id is empty"};
  const size_t points = in.hits().size() + in.misses().size();
  if (points > kMaxPointsPerObservation)
    return Error{std::to_string(points) + " points, more than the limit of " +
                 std::to_string(kMaxPointsPerObservation)};
  copy_points(in.hits(), hits);
  copy_points(in.misses(), misses);
  ObservationView view;
  view.x = in.pose().x();
  view.y = in.pose().y();
  view.theta = in.has_heading() ? in.pose().theta() : 0.0;
  view.has_heading = in.has_heading();
  view.hits = hits;
  view.misses = misses;
  return view;
}

LayoutRequest to_request(const slam::GridConfig& in) {
  return LayoutRequest{in.request_id(), in.resolution(), in.origin().x(),       in.origin().y(),
                       in.width_m(),    in.height_m(),   in.inflation_radius(), in.legacy_mode()};
}

EditRequest to_request(const slam::MapEdit& in) {
  return EditRequest{in.request_id(), static_cast<EditKind>(in.kind()), Vec2{in.point().x(), in.point().y()},
                     in.robot_id().to_string()};
}

FileRequest to_request(const slam::MapFileRequest& in) {
  return FileRequest{in.request_id(), static_cast<FileAction>(in.action()), in.yaml_path().to_string(),
                     in.robot_id().to_string()};
}

slam::MapReply to_reply(const RequestReply& in) {
  slam::MapReply r;
  r.request_id(in.request_id);
  switch (in.result) {
    case RequestResult::Ok:
      r.result(slam::MAP_OK);
      break;
    case RequestResult::InvalidRequest:
      r.result(slam::MAP_INVALID_REQUEST);
      break;
    case RequestResult::IoError:
      r.result(slam::MAP_IO_ERROR);
      break;
    case RequestResult::BadFile:
      r.result(slam::MAP_BAD_FILE);
      break;
    case RequestResult::UnknownRobot:
      r.result(slam::MAP_UNKNOWN_ROBOT);
      break;
  }
  r.message(in.message.substr(0, 511));  // string<512>
  return r;
}

void fill_snapshot(const OccupancyGrid& grid, uint32_t layout_id, uint64_t version, int64_t stamp_ns,
                   slam::GridSnapshot* out) {
  out->layout_id(layout_id);
  out->version(version);
  out->stamp_ns(stamp_ns);
  slam::GridInfo& info = out->info();
  info.width(static_cast<uint32_t>(grid.width()));
  info.height(static_cast<uint32_t>(grid.height()));
  info.resolution(grid.resolution());
  info.origin().x(grid.origin_x());
  info.origin().y(grid.origin_y());
  info.inflation_radius(grid.config().inflation_radius);
  const auto classes = grid.classes();
  out->cells().assign(classes.begin(), classes.end());
}

void fill_patch(const OccupancyGrid& grid, uint32_t layout_id, uint64_t version, int64_t stamp_ns,
                EncodedTiles& encoded, slam::GridTiles* out) {
  encode_tiles(grid.classes(), grid.dirty_tiles(), encoded);
  out->layout_id(layout_id);
  out->version(version);
  out->stamp_ns(stamp_ns);
  out->tile_side(static_cast<uint16_t>(grid.dirty_tiles().layout().side));
  out->encoding(static_cast<uint8_t>(encoded.encoding));
  out->tiles().assign(encoded.tiles.begin(), encoded.tiles.end());
  out->data().assign(encoded.data.begin(), encoded.data.end());
}

void fill_correction(const correction::RobotCorrection& in, int64_t stamp_ns, slam::PoseCorrection* out) {
  out->robot_id(in.robot);
  out->version(in.version);
  out->stamp_ns(stamp_ns);
  out->map_from_odom().x(in.map_from_odom.x);
  out->map_from_odom().y(in.map_from_odom.y);
  out->map_from_odom().theta(in.map_from_odom.theta);
  const Eigen::Matrix3d& c = in.covariance;
  out->covariance({c(0, 0), c(0, 1), c(0, 2), c(1, 1), c(1, 2), c(2, 2)});
  out->segment(in.segment);
  out->keyframes(in.keyframes);
  out->loop_closures(in.loop_closures);
  switch (in.placement) {
    case correction::Placement::Placed:
      out->placement(slam::PLACEMENT_PLACED);
      break;
    case correction::Placement::Placing:
      out->placement(slam::PLACEMENT_PLACING);
      break;
    case correction::Placement::Unplaced:
      out->placement(slam::PLACEMENT_UNPLACED);
      break;
    case correction::Placement::Lost:
      out->placement(slam::PLACEMENT_LOST);
      break;
  }
  out->localisation_score(in.localisation_score);
  switch (in.source) {
    case correction::CorrectionSource::Identity:
      out->source(slam::CORRECTION_IDENTITY);
      break;
    case correction::CorrectionSource::Match:
      out->source(slam::CORRECTION_MATCH);
      break;
    case correction::CorrectionSource::Loop:
      out->source(slam::CORRECTION_LOOP);
      break;
    case correction::CorrectionSource::Operator:
      out->source(slam::CORRECTION_OPERATOR);
      break;
    case correction::CorrectionSource::Restored:
      out->source(slam::CORRECTION_RESTORED);
      break;
  }
}

}  // namespace slam::mapper
