// Cyclone entity set-up and the IDL conversions. Every return code is checked; a failed write is
// reported to the loop, which counts and logs it.
#include "simulator/dds/sim_dds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "common/core/bounded_text.hpp"
#include "common/core/clock.hpp"
#include "common/core/topics.hpp"

namespace slam::sim {
namespace {

constexpr int kTakeBatch = 16;

Result<ControlCommand> to_command(const slam_SimControl& s) {
  ControlCommand c;
  c.command_id = s.command_id;
  switch (s.kind) {
    case slam_SIM_SPAWN:
      c.kind = ControlKind::Spawn;
      break;
    case slam_SIM_REMOVE:
      c.kind = ControlKind::Remove;
      break;
    case slam_SIM_PAUSE:
      c.kind = ControlKind::Pause;
      break;
    case slam_SIM_RESUME:
      c.kind = ControlKind::Resume;
      break;
    case slam_SIM_SET_WORLD:
      c.kind = ControlKind::SetWorld;
      break;
    case slam_SIM_SET_NOISE:
      c.kind = ControlKind::SetNoise;
      break;
    case slam_SIM_SET_SPEED:
      c.kind = ControlKind::SetSpeed;
      break;
    default:
      return Error{
          fmt::format("control {}: unknown command kind {}", s.command_id, static_cast<int>(s.kind))};
  }
  c.count = s.count;
  c.poses.reserve(s.poses._length);
  for (uint32_t i = 0; i < s.poses._length; ++i)
    c.poses.push_back({s.poses._buffer[i].x, s.poses._buffer[i].y, s.poses._buffer[i].theta});
  c.robot_id.assign(s.robot_id, strnlen(s.robot_id, sizeof s.robot_id));
  c.world.assign(s.world, strnlen(s.world, sizeof s.world));
  c.range_noise_sd = s.range_noise_sd;
  c.dropout = s.dropout;
  c.odometry_drift = s.odometry_drift;
  c.speed_factor = s.speed_factor;
  return c;
}

slam_Pose2 to_idl(const Pose& p) {
  return {p.x, p.y, p.theta};
}

}  // namespace

Result<std::unique_ptr<SimDds>> SimDds::create(int domain) {
  std::unique_ptr<SimDds> dds(new SimDds());
  dds->participant_ =
      cyclone::Entity(dds_create_participant(static_cast<dds_domainid_t>(domain), nullptr, nullptr));
  if (!dds->participant_.ok())
    return Error{
        fmt::format("Cyclone participant on domain {}: {}", domain, dds_strretcode(dds->participant_.get()))};
  const dds_entity_t p = dds->participant_.get();

  auto control_topic = cyclone::make_topic(p, &slam_SimControl_desc, topics::kSimControl);
  if (!control_topic) return control_topic.error();
  const auto qos = cyclone::make_qos(topics::kSimControl.qos);
  dds->control_reader_ = dds_create_reader(p, *control_topic, qos.get(), nullptr);
  if (dds->control_reader_ < 0)
    return Error{
        fmt::format("Cyclone reader {}: {}", topics::kSimControl.name, dds_strretcode(dds->control_reader_))};

  auto reply = cyclone::make_writer(p, &slam_SimReply_desc, topics::kSimReply);
  if (!reply) return reply.error();
  dds->reply_writer_ = *reply;
  auto world = cyclone::make_writer(p, &slam_SimWorld_desc, topics::kSimWorld);
  if (!world) return world.error();
  dds->world_writer_ = *world;
  auto truth = cyclone::make_writer(p, &slam_SimGroundTruth_desc, topics::kSimGroundTruth);
  if (!truth) return truth.error();
  dds->truth_writer_ = *truth;
  return dds;
}

Status SimDds::take_controls(std::vector<ControlCommand>& out, std::vector<UnreadableControl>& unreadable) {
  for (;;) {
    void* samples[kTakeBatch] = {};
    dds_sample_info_t infos[kTakeBatch];
    const dds_return_t n = dds_take(control_reader_, samples, infos, kTakeBatch, kTakeBatch);
    if (n < 0) return Error{fmt::format("taking {}: {}", topics::kSimControl.name, dds_strretcode(n))};
    for (dds_return_t i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      const auto& sample = *static_cast<const slam_SimControl*>(samples[i]);
      auto c = to_command(sample);
      if (c)
        out.push_back(std::move(*c));
      else
        unreadable.push_back({sample.command_id, c.message()});
    }
    if (n > 0) dds_return_loan(control_reader_, samples, n);
    if (n < kTakeBatch) return {};
  }
}

Status SimDds::publish_reply(uint64_t command_id, const Status& result) {
  slam_SimReply sample{};
  sample.command_id = command_id;
  sample.ok = static_cast<bool>(result);
  if (!result) cyclone::copy_bounded(result.message(), sample.message, sizeof sample.message);
  const dds_return_t rc = dds_write(reply_writer_, &sample);
  if (rc != DDS_RETCODE_OK)
    return Error{fmt::format("writing {}: {}", topics::kSimReply.name, dds_strretcode(rc))};
  return {};
}

Status SimDds::publish_world(const World& world) {
  const auto walls = world.walls();
  walls_.resize(walls.size());
  for (size_t i = 0; i < walls.size(); ++i)
    walls_[i] = {{walls[i].a.x, walls[i].a.y}, {walls[i].b.x, walls[i].b.y}};
  slam_SimWorld sample{};
  cyclone::copy_bounded(world.name(), sample.name, sizeof sample.name);
  sample.width_m = world.bounds().width();
  sample.height_m = world.bounds().height();
  sample.walls = {static_cast<uint32_t>(walls_.size()), static_cast<uint32_t>(walls_.size()), walls_.data(),
                  false};
  const dds_return_t rc = dds_write(world_writer_, &sample);
  if (rc != DDS_RETCODE_OK)
    return Error{fmt::format("writing {}: {}", topics::kSimWorld.name, dds_strretcode(rc))};
  return {};
}

Status SimDds::publish_truth(const Simulation& sim) {
  const auto robots = sim.robots();
  truth_.resize(robots.size());
  for (size_t i = 0; i < robots.size(); ++i) {
    cyclone::copy_bounded(robots[i].id, truth_[i].robot_id, sizeof truth_[i].robot_id);
    truth_[i].true_pose = to_idl(robots[i].true_pose);
    truth_[i].reported_pose = to_idl(robots[i].reported_pose);
  }
  slam_SimGroundTruth sample{};
  sample.stamp_ns = now_ns();
  sample.paused = sim.paused();
  sample.robots = {static_cast<uint32_t>(truth_.size()), static_cast<uint32_t>(truth_.size()), truth_.data(),
                   false};
  const dds_return_t rc = dds_write(truth_writer_, &sample);
  if (rc != DDS_RETCODE_OK)
    return Error{fmt::format("writing {}: {}", topics::kSimGroundTruth.name, dds_strretcode(rc))};
  return {};
}

}  // namespace slam::sim
