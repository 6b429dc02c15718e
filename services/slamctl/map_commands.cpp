#include "slamctl/map_commands.hpp"

#include "slamctl/session_io.hpp"

namespace slam::ctl {
namespace {

int cmd_map_file(Session& s, MapFileAction action, const std::string& yaml_path) {
  MapFileRequest req;
  req.action(action);
  req.yaml_path(yaml_path);
  return map_request(s, dds::kMapFileRequest, req,
                     (action == MAP_EXPORT ? "map saved to " : "map loaded from ") + yaml_path);
}

}  // namespace

Handler add_map(CLI::App& cli) {
  auto file = std::make_shared<std::string>();
  cli.require_subcommand(1);
  auto* save = cli.add_subcommand("save", "export the map to FILE.yaml");
  save->add_option("file", *file, "YAML path")->required();
  auto* load = cli.add_subcommand("load", "import FILE.yaml as a prior");
  load->add_option("file", *file, "YAML path")->required();
  return
      [file, save](Session& s) { return cmd_map_file(s, save->parsed() ? MAP_EXPORT : MAP_IMPORT, *file); };
}

namespace {

struct TrajectoryArgs {
  std::string robot;
  std::string file;
  std::string format = "tum";
};

// The mapper writes the file and answers with how many poses, from which stamp to which.
int cmd_trajectory(Session& s, const TrajectoryArgs& a) {
  MapFileRequest req;
  req.action(a.format == "carmen" ? MAP_EXPORT_TRAJECTORY_CARMEN : MAP_EXPORT_TRAJECTORY_TUM);
  req.yaml_path(a.file);
  req.robot_id(a.robot);
  return map_request(s, dds::kMapFileRequest, req, "trajectory of " + a.robot + " written to " + a.file);
}

}  // namespace

Handler add_trajectory(CLI::App& cli) {
  auto a = std::make_shared<TrajectoryArgs>();
  cli.add_option("robot", a->robot, "robot id")->required();
  cli.add_option("file", a->file, "the file to write, on the mapper's disk (its directory must exist)")
      ->required();
  cli.add_option(
         "--format", a->format,
         "tum: 'stamp x y z qx qy qz qw' lines; carmen: 'ODOM x y theta 0 0 0 stamp host stamp' lines")
      ->check(CLI::IsMember({"tum", "carmen"}))
      ->capture_default_str();
  return [a](Session& s) { return cmd_trajectory(s, *a); };
}

namespace {

struct GridArgs {
  double resolution = 0.05;
  double width = 0;
  double height = 0;
  double inflation = -1;
  std::vector<double> origin;
  bool legacy = false;
};

int cmd_grid(Session& s, const GridArgs& a) {
  GridConfig c;
  c.resolution(a.resolution);
  c.width_m(a.width);
  c.height_m(a.height);
  c.origin(a.origin.size() == 2 ? point(a.origin[0], a.origin[1]) : point(0, 0));
  c.inflation_radius(a.inflation);
  c.legacy_mode(a.legacy);
  char done[160];
  std::snprintf(done, sizeof done, "grid set to %.3f m cells%s: the mapper rebuilt the map from its store",
                a.resolution, a.legacy ? " (legacy)" : "");
  return map_request(s, dds::kGridConfig, c, done);
}

}  // namespace

Handler add_grid(CLI::App& cli) {
  auto a = std::make_shared<GridArgs>();
  cli.add_option("--resolution", a->resolution, "metres per cell")->check(CLI::PositiveNumber)->required();
  cli.add_option("--width", a->width, "metres (0: keep growing as robots explore)");
  cli.add_option("--height", a->height, "metres");
  cli.add_option("--origin", a->origin, "x y of the lower-left corner")->expected(2);
  cli.add_option("--inflation", a->inflation, "robot radius in metres for the restricted layer");
  cli.add_flag("--legacy", a->legacy, "2019 behaviour: points obstruct their cell, nothing is cleared");
  return [a](Session& s) { return cmd_grid(s, *a); };
}

namespace {

int cmd_map_edit(Session& s, MapEditKind kind, const Point2& point, const std::string& robot) {
  MapEdit edit;
  edit.kind(kind);
  edit.point(point);
  edit.robot_id(robot);
  char done[160];
  switch (kind) {
    case EDIT_OBSTRUCT:
      std::snprintf(done, sizeof done, "cell at (%.2f, %.2f) obstructed", point.x(), point.y());
      break;
    case EDIT_UNOBSTRUCT:
      std::snprintf(done, sizeof done, "obstruction at (%.2f, %.2f) removed", point.x(), point.y());
      break;
    default:
      std::snprintf(done, sizeof done, "observations of %s deleted, map rebuilt", robot.c_str());
      break;
  }
  return map_request(s, dds::kMapEdit, edit, done);
}

// obstruct and unobstruct: one cell, x y.
Handler add_cell_edit(CLI::App& cli, MapEditKind kind) {
  auto cell = std::make_shared<std::vector<double>>();
  cli.add_option("xy", *cell, "x y in metres")->expected(2)->required();
  return [cell, kind](Session& s) { return cmd_map_edit(s, kind, point((*cell)[0], (*cell)[1]), ""); };
}

}  // namespace

Handler add_obstruct(CLI::App& cli) {
  return add_cell_edit(cli, EDIT_OBSTRUCT);
}

Handler add_unobstruct(CLI::App& cli) {
  return add_cell_edit(cli, EDIT_UNOBSTRUCT);
}

Handler add_reset(CLI::App& cli) {
  auto robot = std::make_shared<std::string>();
  cli.add_option("robot", *robot, "robot id")->required();
  return [robot](Session& s) { return cmd_map_edit(s, EDIT_RESET_ROBOT, point(0, 0), *robot); };
}

}  // namespace slam::ctl
