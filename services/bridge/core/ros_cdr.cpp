// CDR of nav_msgs/msg/OccupancyGrid and its ros2msg definition (see ros_cdr.hpp).
#include "bridge/core/ros_cdr.hpp"

#include <bit>
#include <cstdint>
#include <cstring>

#include "bridge/core/foxglove_messages.hpp"

namespace slam::bridge {
namespace {

static_assert(std::endian::native == std::endian::little, "the CDR below is written as little endian");

// Plain CDR: each primitive aligned to its size, counted from the end of the encapsulation header.
class CdrWriter {
 public:
  explicit CdrWriter(std::string& out) : out_(out) {
    out_.append("\x00\x01\x00\x00", 4);  // CDR_LE, no options
  }
  template <class T>
  void put(T value) {
    align(sizeof(T));
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out_.append(bytes, sizeof(T));
  }
  void put_string(const std::string& s) {
    put(static_cast<uint32_t>(s.size() + 1));
    out_.append(s);
    out_.push_back('\0');
  }
  void put_time(const RosTime& t) {
    put(t.sec);
    put(t.nanosec);
  }

 private:
  void align(size_t n) {
    while ((out_.size() - 4) % n != 0) out_.push_back('\0');
  }
  std::string& out_;
};

}  // namespace

// The ROS 2 message definitions (common_interfaces, rcl_interfaces), comments left out.
const char* const kOccupancyGridDefinition =
    "std_msgs/Header header\n"
    "MapMetaData info\n"
    "int8[] data\n"
    "================================================================================\n"
    "MSG: std_msgs/Header\n"
    "builtin_interfaces/Time stamp\n"
    "string frame_id\n"
    "================================================================================\n"
    "MSG: builtin_interfaces/Time\n"
    "int32 sec\n"
    "uint32 nanosec\n"
    "================================================================================\n"
    "MSG: nav_msgs/MapMetaData\n"
    "builtin_interfaces/Time map_load_time\n"
    "float32 resolution\n"
    "uint32 width\n"
    "uint32 height\n"
    "geometry_msgs/Pose origin\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Pose\n"
    "Point position\n"
    "Quaternion orientation\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Point\n"
    "float64 x\n"
    "float64 y\n"
    "float64 z\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Quaternion\n"
    "float64 x 0\n"
    "float64 y 0\n"
    "float64 z 0\n"
    "float64 w 1\n";

std::string occupancy_grid_cdr(const OccupancyGridOut& grid) {
  std::string out;
  out.reserve(grid.data.size() + 128);
  CdrWriter w(out);
  w.put_time(grid.stamp);  // header
  w.put_string(kMapFrame);
  w.put_time(grid.stamp);  // info.map_load_time
  w.put(grid.resolution);
  w.put(grid.width);
  w.put(grid.height);
  for (double v : {grid.origin.x, grid.origin.y, 0.0, 0.0, 0.0, 0.0, 1.0}) w.put(v);  // position, orientation
  w.put(static_cast<uint32_t>(grid.data.size()));
  out.append(reinterpret_cast<const char*>(grid.data.data()), grid.data.size());
  return out;
}

}  // namespace slam::bridge
